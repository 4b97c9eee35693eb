// core.include: evaluates a file in the global scope, once; relative paths are
// relative to this script's folder; a missing file or an error inside the
// included file is a catchable Error naming that file and line.
// Arguments: <tests/data> <shared data> <tmp>.
"use strict";
const [dataDir] = core.scriptArguments();

// Include works: the helpers become globals.
const first = core.include("test_asserts.js");
if (first !== true) throw new Error("core.include(\"test_asserts.js\"): expected true, got " + first);
expectEqual([typeof expectEqual, typeof expectThrows, typeof checked], ["function", "function", "number"],
            "test_asserts.js globals");

// Each file once: again, by another path, by an absolute path, or the running script itself.
const scripts = dataDir + "/../plugin/scripts";
expectEqual(core.include("test_asserts.js"), false, "including a file twice is a no-op");
expectEqual(core.include("./include_fixtures/../test_asserts.js"), false, "the same file by another relative path");
expectEqual(core.include(scripts + "/test_asserts.js"), false, "the same file by an absolute path");
expectEqual(core.include("include_test.js"), false, "the running script itself");

// Functions and vars are shared; top-level let/const are not.
expectEqual(core.include(scripts + "/include_fixtures/globals.js"), true, "an absolute path");
expectEqual([includedFunction(), includedVar, typeof includedLet, typeof includedConst],
            ["from globals.js", 2, "undefined", "undefined"], "globals of globals.js");

// A cycle: cycle_a includes cycle_b, which includes cycle_a (still being included): a no-op.
expectEqual(core.include("include_fixtures/cycle_a.js"), true, "include cycle_a.js");
expectEqual(cycleLog, ["a", "b includes a: false", "a includes b: true"], "cycle_a.js ran once");

// Errors.
expectThrows(() => core.include("include_fixtures/no_such_file.js"), "InputError",
             "core.include: ", "/include_fixtures/no_such_file.js: no such file");
expectThrows(() => core.include("include_fixtures"), "InputError", "/include_fixtures: not a file");
expectThrows(() => core.include(5), "ArgumentError", "core.include: path must be a string, got the number 5");
expectThrows(() => core.include(""), "ArgumentError", "path must be a non-empty string");
expectThrows(() => core.include("include_fixtures/runtime_error.js"), "ReferenceError",
             "core.include: ", "/include_fixtures/runtime_error.js:4: ReferenceError: notDefinedAnywhere is not defined");
expectEqual(beforeTheError, true, "what ran before the error stays defined");
// A failed file is not marked as included: it fails again.
expectThrows(() => core.include("include_fixtures/runtime_error.js"), "ReferenceError", "/runtime_error.js:4: ");
expectThrows(() => core.include("include_fixtures/syntax_error.js"), "SyntaxError",
             "core.include: ", "/include_fixtures/syntax_error.js:3: SyntaxError: ");
expectThrows(() => core.include("include_fixtures/slot_error.js"), "ArgumentError",
             "core.include: ", "/include_fixtures/slot_error.js:3: ArgumentError: core.objectInfo: no object with id 42");
expectThrows(() => core.include("include_fixtures/nested_error.js"), "ReferenceError",
             "core.include: ", "/include_fixtures/nested_error.js:3: ReferenceError: core.include: ",
             "/include_fixtures/runtime_error.js:4: ReferenceError: notDefinedAnywhere is not defined");
print("include: ok (" + checked + " errors checked)");
