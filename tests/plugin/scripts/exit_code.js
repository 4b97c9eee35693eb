// core.exitApplication(3) stops the script at once with exit code 3: a
// try/catch cannot swallow it, finally blocks still run.
"use strict";
print("before exit");
try {
  core.exitApplication(3);
  print("not reached: after exitApplication");
} catch (error) {
  print("not reached: caught " + error);
} finally {
  print("finally still runs");
}
print("not reached: after the try");
