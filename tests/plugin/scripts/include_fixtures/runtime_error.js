// Included by include_test.js: fails on line 4, after defining a global.
"use strict";
var beforeTheError = true;
notDefinedAnywhere();
