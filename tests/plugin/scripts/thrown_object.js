// A thrown value that is not an Error is reported by its message when it
// has one (run_and_check): `throw {name, message}` printed "[object Object]".
"use strict";
print("before the throw");
throw {name: "StageFailed", message: "the instance stage found no cache"};  // line 5
