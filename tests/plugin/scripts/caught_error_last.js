// A script (or an included file) whose last statement's value is an error
// it caught ran to its end: exit 0, its promises' callbacks run, and the
// include succeeds (run_and_check). The host took the Error value for an
// uncaught throw: exit 1, "InputError: ..." and no callbacks.
"use strict";
Promise.resolve().then(() => print("then ran"));
print("included: " + core.include("caught_error_part.js"));
let caught = null;
try {
  core.loadObject("no_such_garment.obj");
} catch (error) {
  caught = error;
}
caught;
