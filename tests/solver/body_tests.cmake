# body_tests: the skinned MakeHuman body (loading, binding, skinning), its
# collision scene (BVH closest point, pseudo-normal sign, resolve, friction)
# and the JSON reader it loads with; whether a tube garment can go round it.
# One executable, a file per topic: MeshBody on built meshes, the MakeHuman
# body, its waist, its malformed files; mesh_oracles (brute force, test
# meshes) and skinned_body_fixture (the body, loaded once) are shared.
mrcloth_add_gtest(body_test
  ${CMAKE_CURRENT_LIST_DIR}/mesh_body_test.cpp ${CMAKE_CURRENT_LIST_DIR}/skinned_body_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/skinned_waist_test.cpp ${CMAKE_CURRENT_LIST_DIR}/skinned_body_files_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh_oracles.cpp ${CMAKE_CURRENT_LIST_DIR}/skinned_body_fixture.cpp
  ${CMAKE_CURRENT_LIST_DIR}/json_lite_test.cpp LIBS mrcloth::solver)
mrcloth_add_gtest(capsule_rig_test ${CMAKE_CURRENT_LIST_DIR}/capsule_rig_test.cpp LIBS mrcloth::solver)
mrcloth_add_gtest(body_surface_test ${CMAKE_CURRENT_LIST_DIR}/body_surface_test.cpp LIBS mrcloth::solver)
mrcloth_add_gtest(arm_clearance_test ${CMAKE_CURRENT_LIST_DIR}/arm_clearance_test.cpp LIBS mrcloth::solver)
mrcloth_add_gtest(character_setup_test ${CMAKE_CURRENT_LIST_DIR}/character_setup_test.cpp LIBS mrcloth::solver)
mrcloth_add_gtest(garment_fit_test ${CMAKE_CURRENT_LIST_DIR}/garment_fit_test.cpp LIBS mrcloth::solver)
