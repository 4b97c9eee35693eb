// Included by include_test.js: a slot's ArgumentError on line 3.
"use strict";
core.objectInfo(42);
