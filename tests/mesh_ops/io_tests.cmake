# io tests (garment_io, units)
