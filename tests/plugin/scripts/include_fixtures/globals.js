// Included by include_test.js: function declarations and `var`s become
// globals; top-level let/const stay private to this file.
function includedFunction() { return "from globals.js"; }
var includedVar = 2;
let includedLet = 3;
const includedConst = 4;
