// A value whose toString throws: core.print, core.log and core.warn throw
// the error on to the script (once, the error's text was printed and the
// script went on, exit 0).
"use strict";
const throwing = {toString() { throw new Error("toString boom"); }};
for (const name of ["print", "log", "warn"]) {
  let caught = null;
  try {
    core[name](throwing);
  } catch (error) {
    caught = error;
  }
  if (!caught || caught.message !== "toString boom") throw new Error("core." + name + " did not throw: " + caught);
}
core.print({toString() { return "a toString that works"; }});
core.print({toString() { throw new Error("uncaught toString boom"); }});
core.print("not reached");
