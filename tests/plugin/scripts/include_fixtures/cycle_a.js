// Included by include_test.js; includes cycle_b.js, which includes this file
// again (relative paths are relative to the running script's folder).
var cycleLog = (typeof cycleLog === "undefined" ? [] : cycleLog).concat(["a"]);
cycleLog.push("a includes b: " + core.include("include_fixtures/cycle_b.js"));
