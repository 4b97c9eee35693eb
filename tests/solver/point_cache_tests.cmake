# point_cache_tests
