# Refinement, hierarchy, hanging nodes, balance, mass and mode-layer tests.
mrcloth_add_gtest(refine_test
  ${CMAKE_CURRENT_LIST_DIR}/uniform_refine_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/adaptive_refine_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/lumped_mass_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mode_layer_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mode_mapping_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mode_painting_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/save_load_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh_invariants.cpp
  LIBS mrcloth::mesh_ops)
