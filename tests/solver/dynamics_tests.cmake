# dynamics_tests
