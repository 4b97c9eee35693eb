// Included by include_test.js: the error is in the file this one includes (line 3).
"use strict";
core.include("include_fixtures/runtime_error.js");
