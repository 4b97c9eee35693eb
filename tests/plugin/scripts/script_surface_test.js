// What scripts see of core and the plugins: their calls, not the signals
// the host listens to. A script calling multirescloth.log(...) wrote fake
// "[warn]" lines, startJob left a job never finished, log(99, ...) dropped
// its text. Object.prototype's names (toString) still read through, and the
// argument check holds for calls named like them.
"use strict";
core.include("test_asserts.js");

for (const [name, object] of [["multirescloth", multirescloth], ["preview", preview]])
  for (const signal of ["log", "startJob", "setJobState", "finishJob", "objectNameChanged", "destroyed"])
    expectEqual(typeof object[signal], "undefined", name + "." + signal);
for (const signal of ["objectNameChanged", "destroyed"]) expectEqual(typeof core[signal], "undefined", "core." + signal);
// Not listed either: `in`, for...in and Object.keys show the calls alone.
const listed = [];
for (const key in multirescloth) listed.push(key);
expectEqual([listed.includes("startJob"), "log" in preview, Object.keys(multirescloth).includes("log")], [false, false, false],
            "signals listed");
expectEqual([listed.includes("refineUniform"), "render" in preview], [true, true], "calls listed");
expectEqual(typeof core.log, "function", "core.log (a call of core's, not a signal)");
expectEqual([typeof core.print, typeof multirescloth.refineUniform, typeof preview.render], ["function", "function", "function"],
            "the calls");
expectEqual(String(multirescloth).indexOf("MultiresClothPlugin") >= 0, true, "toString reads through");
expectThrows(() => multirescloth.refineUniform(1, 2, 3), "ArgumentError", "takes at most 2 arguments, got 3");
print("script surface: ok");
