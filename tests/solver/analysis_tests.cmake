# analysis_tests: instance analysis (curvature, features, k-means, deformation modes)
mrcloth_add_gtest(analysis_test ${CMAKE_CURRENT_LIST_DIR}/kmeans_test.cpp ${CMAKE_CURRENT_LIST_DIR}/instance_curvature_test.cpp
                  ${CMAKE_CURRENT_LIST_DIR}/deformation_modes_test.cpp LIBS mrcloth::solver)
