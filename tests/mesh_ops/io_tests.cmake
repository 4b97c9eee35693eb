# io tests (garment_io, units, texture coordinates)
# garment_io_test: one executable, a file per topic (loading good files and
# units, refusing bad files, saving and exporting); garment_io_support holds
# the scratch folder and the grid files they share.
mrcloth_add_gtest(garment_io_test garment_load_test.cpp garment_load_errors_test.cpp garment_save_test.cpp
  garment_io_support.cpp LIBS mrcloth::mesh_ops)
mrcloth_add_gtest(texture_coords_test texture_coords_test.cpp LIBS mrcloth::mesh_ops)
mrcloth_add_gtest(atomic_file_test atomic_file_test.cpp LIBS mrcloth::mesh_ops)
mrcloth_add_gtest(input_mutation_test input_mutation_test.cpp mesh_invariants.cpp LIBS mrcloth::mesh_ops)
