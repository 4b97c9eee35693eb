# Bend partners and boundary loops.
mrcloth_add_gtest(topology_test
  ${CMAKE_CURRENT_LIST_DIR}/bend_partners_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/boundary_loops_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh_invariants.cpp
  LIBS mrcloth::mesh_ops)
