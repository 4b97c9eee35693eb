# colliders_tests
