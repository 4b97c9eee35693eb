# io tests (garment_io, units)
mrcloth_add_gtest(garment_io_test garment_io_test.cpp LIBS mrcloth::mesh_ops)
