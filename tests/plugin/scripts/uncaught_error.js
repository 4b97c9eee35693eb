// An uncaught error stops the script: mrcloth prints "<file>:<line>: <error>"
// and the JS stack, and exits 1 (checked by run_and_check.cmake).
"use strict";
print("before the error");

function refineMissingObject() {
  return multirescloth.refineUniform(42, 1);  // line 7: no object 42
}

refineMissingObject();
print("not reached");
