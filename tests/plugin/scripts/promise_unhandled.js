// A promise rejected with no handler is an uncaught error: mrcloth prints
// "<file>:<line>: uncaught (in promise) <error>" for each, once every
// callback has run, and exits 1 (checked by run_and_check.cmake).
"use strict";
function refine() {
  return Promise.resolve().then(() => multirescloth.refineUniform(42, 1));  // line 6: no object 42
}
refine();
Promise.resolve().then(() => print("callbacks still run"));
Promise.reject(7);
Promise.resolve().then(() => Promise.reject(new Error("returned rejected")));  // line 11: the derived promise takes it
Promise.resolve().then(() => Promise.reject(new Error("caught"))).catch(() => print("a caught one is no error"));
print("script done");
