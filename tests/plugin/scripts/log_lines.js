// Every line of a multi-line message carries its prefix (run_and_check):
// grep "^\[warn\]" missed a warning's second line.
"use strict";
core.warn("first\nsecond");
core.log("one\ntwo");
