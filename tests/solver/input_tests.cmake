# input_tests: the solver's readers (BVH, PC2, cache OBJ, JSON, the MakeHuman body files) under seeded edits
mrcloth_add_gtest(solver_input_mutation_test ${CMAKE_CURRENT_LIST_DIR}/input_mutation_test.cpp LIBS mrcloth::solver)
