// Included by include_test.js: does not compile (line 3).
var fine = 1;
const broken = ;
