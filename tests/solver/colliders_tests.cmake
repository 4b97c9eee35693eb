# colliders_tests: analytic colliders (distances, normals, resolution, friction)
mrcloth_add_gtest(colliders_test ${CMAKE_CURRENT_LIST_DIR}/colliders_test.cpp LIBS mrcloth::solver)
