# motion_tests: BVH reading/writing, forward kinematics, pose interpolation and blending
mrcloth_add_gtest(motion_test ${CMAKE_CURRENT_LIST_DIR}/bvh_test.cpp ${CMAKE_CURRENT_LIST_DIR}/skeleton_test.cpp LIBS mrcloth::solver)
