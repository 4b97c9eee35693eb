# measures_tests: material coordinates, evaluation at material points, distances, wrinkle energy
mrcloth_add_gtest(detail_measures_test ${CMAKE_CURRENT_LIST_DIR}/detail_measures_test.cpp LIBS mrcloth::solver)
mrcloth_add_gtest(result_comparison_test ${CMAKE_CURRENT_LIST_DIR}/result_comparison_test.cpp LIBS mrcloth::solver)
