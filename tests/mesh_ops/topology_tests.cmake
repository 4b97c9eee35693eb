# bend partner and boundary loop tests
