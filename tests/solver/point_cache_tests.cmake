# point_cache_tests: PC2 writer/reader and OBJ sequences
mrcloth_add_gtest(point_cache_test ${CMAKE_CURRENT_LIST_DIR}/point_cache_test.cpp LIBS mrcloth::solver)
