# body_tests
