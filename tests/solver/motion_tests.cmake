# motion_tests
