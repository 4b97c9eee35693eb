# Dynamics model, spring derivatives, integrator and simulation driver.
# The integrator's tests are a file per topic (the solve, strain limiting,
# contacts, T-nodes); implicit_integrator_support holds what they share.
mrcloth_add_gtest(dynamics_test
  ${CMAKE_CURRENT_LIST_DIR}/spring_energy_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/dynamics_model_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/implicit_integrator_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/implicit_integrator_limiter_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/implicit_integrator_contact_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/implicit_integrator_tnode_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/implicit_integrator_support.cpp
  ${CMAKE_CURRENT_LIST_DIR}/drape_consistency_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/self_contact_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/worker_pool_test.cpp
  LIBS mrcloth::solver)
