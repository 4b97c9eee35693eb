# body_tests: the skinned MakeHuman body (loading, binding, skinning), its
# collision scene (BVH closest point, pseudo-normal sign, resolve, friction)
# and the JSON reader it loads with; whether a tube garment can go round it.
mrcloth_add_gtest(body_test ${CMAKE_CURRENT_LIST_DIR}/skinned_body_test.cpp ${CMAKE_CURRENT_LIST_DIR}/json_lite_test.cpp LIBS mrcloth::solver)
mrcloth_add_gtest(capsule_rig_test ${CMAKE_CURRENT_LIST_DIR}/capsule_rig_test.cpp LIBS mrcloth::solver)
mrcloth_add_gtest(body_surface_test ${CMAKE_CURRENT_LIST_DIR}/body_surface_test.cpp LIBS mrcloth::solver)
mrcloth_add_gtest(arm_clearance_test ${CMAKE_CURRENT_LIST_DIR}/arm_clearance_test.cpp LIBS mrcloth::solver)
mrcloth_add_gtest(character_setup_test ${CMAKE_CURRENT_LIST_DIR}/character_setup_test.cpp LIBS mrcloth::solver)
mrcloth_add_gtest(garment_fit_test ${CMAKE_CURRENT_LIST_DIR}/garment_fit_test.cpp LIBS mrcloth::solver)
