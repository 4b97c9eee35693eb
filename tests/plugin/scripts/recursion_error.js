// A runaway recursion's uncaught RangeError prints its innermost and
// outermost frames and how many are left out between (run_and_check): its
// stack of about 1,200 frames was printed whole.
"use strict";
function down(n) {
  return down(n + 1) + 1;
}
down(0);
