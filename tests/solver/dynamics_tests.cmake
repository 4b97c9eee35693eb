# Dynamics model, spring derivatives, integrator and simulation driver.
mrcloth_add_gtest(dynamics_test
  ${CMAKE_CURRENT_LIST_DIR}/spring_energy_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/dynamics_model_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/implicit_integrator_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/drape_consistency_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/self_contact_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/worker_pool_test.cpp
  LIBS mrcloth::solver)
