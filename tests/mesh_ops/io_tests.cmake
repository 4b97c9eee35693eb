# io tests (garment_io, units, texture coordinates)
mrcloth_add_gtest(garment_io_test garment_io_test.cpp LIBS mrcloth::mesh_ops)
mrcloth_add_gtest(texture_coords_test texture_coords_test.cpp LIBS mrcloth::mesh_ops)
mrcloth_add_gtest(atomic_file_test atomic_file_test.cpp LIBS mrcloth::mesh_ops)
