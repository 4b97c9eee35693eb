// An object without a prototype (no toString) thrown is named as such
// (run_and_check): its report was the failed conversion's "TypeError: Type error".
"use strict";
throw Object.create(null);  // line 4
