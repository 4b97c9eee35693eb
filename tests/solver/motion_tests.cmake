# motion_tests: BVH reading/writing, forward kinematics, pose interpolation and blending, joint naming conventions, motion axes
mrcloth_add_gtest(motion_test ${CMAKE_CURRENT_LIST_DIR}/bvh_test.cpp ${CMAKE_CURRENT_LIST_DIR}/skeleton_test.cpp ${CMAKE_CURRENT_LIST_DIR}/joint_names_test.cpp ${CMAKE_CURRENT_LIST_DIR}/motion_axes_test.cpp LIBS mrcloth::solver)
