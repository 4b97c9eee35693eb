// Every failure inside a slot reaches the script as a catchable Error whose
// name is the C++ error type and whose message names the call and the problem.
"use strict";
const [dataDir, , tmpDir] = core.scriptArguments();

core.include("test_asserts.js");

core.makePath(tmpDir);
const grid = core.loadObject(dataDir + "/grid3x3.obj");

// Unknown ids.
expectThrows(() => multirescloth.refineUniform(99, 1), "ArgumentError", "multirescloth.refineUniform: ", "no object with id 99");
expectThrows(() => core.objectInfo(42), "ArgumentError", "core.objectInfo: no object with id 42");
// An argument too many is refused (Qt's engine would drop it with a warning:
// saveObject's options were ignored and the garment saved in metres).
expectThrows(() => core.saveObject(grid, tmpDir + "/extra.obj", {units: "cm"}), "ArgumentError",
             "core.saveObject: takes at most 2 arguments, got 3 (see mrcloth --api)");
expectEqual(core.fileExists(tmpDir + "/extra.obj"), false, "a refused call writes nothing");
expectThrows(() => multirescloth.refineUniform(grid, 1, 2), "ArgumentError", "multirescloth.refineUniform: takes at most 2 arguments, got 3");
expectThrows(() => preview.render(grid, tmpDir + "/extra.png", {}, 4), "ArgumentError", "preview.render: takes at most 3 arguments, got 4");
// A slot's own error still names the script's line, not the check's.
try {
  core.objectInfo(4242);
} catch (error) {
  expectEqual(String(error.fileName).endsWith("script_errors_test.js"), true, "fileName of a slot's error: " + error.fileName);
}
// And so does the check's own: the line of the call.
let callLine = 0, thrownLine = -1;
try {
  callLine = new Error().lineNumber + 1;
  core.fileExists("/tmp", 2);
} catch (error) {
  thrownLine = error.lineNumber;
  expectEqual(String(error.fileName).endsWith("script_errors_test.js"), true, "fileName of the check's error: " + error.fileName);
}
expectEqual(thrownLine, callLine, "the line of an argument too many");
// A missing argument is named by the call's own check, not Qt's overload resolution.
expectThrows(() => core.loadObject(), "ArgumentError", "core.loadObject: path must be a string, got undefined");
expectThrows(() => multirescloth.refineUniform(1), "ArgumentError", "multirescloth.refineUniform: ",
             "levels must be an integer, got undefined");
expectThrows(() => preview.contactSheet(), "ArgumentError", "preview.contactSheet: ");
expectThrows(() => multirescloth.getModes(0), "ArgumentError", "no object with id 0");
expectThrows(() => core.deleteObject(7), "ArgumentError", "core.deleteObject: no object with id 7");

// Wrong types and ranges.
expectThrows(() => multirescloth.refineUniform(grid, -1), "ArgumentError", "levels must be an integer >= 0, got -1");
expectThrows(() => multirescloth.refineUniform(grid, 1.5), "ArgumentError", "levels must be an integer, got the number 1.5");
expectThrows(() => multirescloth.refineUniform(grid, "2"), "ArgumentError", "levels must be an integer, got the string \"2\"");
expectThrows(() => multirescloth.refineUniform("1", 1), "ArgumentError", "id must be an integer, got the string \"1\"");
expectThrows(() => multirescloth.refineUniform(undefined, 1), "ArgumentError", "id must be an integer, got undefined");
expectThrows(() => multirescloth.setModes(grid, "all", 2), "ArgumentError", "vertexIds must be an array");
expectThrows(() => multirescloth.setModes(grid, [0, "1"], 2), "ArgumentError", "vertexIds[1] must be an integer");
expectThrows(() => multirescloth.setModes(grid, [16], 2), "ArgumentError", "multirescloth.setModes: ", "16");
expectThrows(() => multirescloth.setModes(grid, [0], -1), "ArgumentError", "multirescloth.setModes: ", "-1");
expectThrows(() => core.exitApplication(256), "ArgumentError", "code must be an integer from 0 to 255, got the number 256");
expectThrows(() => core.exitApplication(1e12), "ArgumentError", "code must be an integer from 0 to 255, got the number 1e+12");

// Options: unknown keys are named with the accepted ones; values are checked.
expectThrows(() => multirescloth.refineAdaptive(grid, {delta: 8, maxlevel: 3}), "ArgumentError",
             "unknown option 'maxlevel'", "accepted: delta, maxLevel, balance");
expectThrows(() => multirescloth.refineAdaptive(grid, {maxLevel: 0}), "ArgumentError", "option 'maxLevel' must be an integer >= 1");
expectThrows(() => multirescloth.refineAdaptive(grid, {delta: "8"}), "ArgumentError", "option 'delta' must be a finite number");
expectThrows(() => multirescloth.refineAdaptive(grid, {delta: Infinity}), "ArgumentError", "option 'delta' must be a finite number");
expectThrows(() => multirescloth.refineAdaptive(grid, {balance: "yes"}), "ArgumentError", "option 'balance' must be true or false");
expectThrows(() => multirescloth.refineAdaptive(grid, 8), "ArgumentError", "options must be an object, got the number 8");
expectThrows(() => multirescloth.paintModes(grid, {center: [0, 0, 0], radius: 1}), "ArgumentError", "missing option 'mode'");
expectThrows(() => multirescloth.paintModes(grid, {center: [0, 0], radius: 1, mode: 2}), "ArgumentError",
             "option 'center' must be an array of 3 numbers");
expectThrows(() => multirescloth.paintModes(grid, {center: [0, 0, 0], radius: 1, mode: 2, size: 3}), "ArgumentError",
             "unknown option 'size'", "accepted: type, center, radius, mode, seeds, layer, threshold, below");
expectThrows(() => multirescloth.paintModes(grid, {center: [0, 0, 0], radius: -1, mode: 2}), "ArgumentError",
             "multirescloth.paintModes: ");
expectThrows(() => multirescloth.exportSurface(grid, tmpDir + "/x.ply", {colorBy: "levels"}), "ArgumentError",
             "option 'colorBy' must be one of \"level\", \"mode\", \"curvature\", \"none\", got the string \"levels\"");
expectThrows(() => multirescloth.exportSurface(grid, tmpDir + "/x.ply", {color: "level"}), "ArgumentError",
             "unknown option 'color'", "accepted: colorBy, triangulate");
expectThrows(() => core.loadObject(dataDir + "/grid3x3.obj", {unit: "dm"}), "ArgumentError",
             "unknown option 'unit'", "accepted: units");
expectThrows(() => core.loadObject(dataDir + "/grid3x3.obj", {units: "furlong"}), "ArgumentError", "furlong");

// Files.
expectThrows(() => core.loadObject(dataDir + "/no_such_garment.obj"), "InputError",
             "core.loadObject: ", "no_such_garment.obj");
expectThrows(() => core.loadObject(""), "ArgumentError", "path must be a non-empty string");
expectThrows(() => core.saveObject(grid, tmpDir + "/grid.xyz"), "ArgumentError", "core.saveObject: ", "grid.xyz");
expectThrows(() => multirescloth.exportSurface(grid, tmpDir + "/no_such_folder/grid.ply"), "OutputError",
             "multirescloth.exportSurface: ", "no_such_folder");

// A failed call changes nothing and the script carries on.
const info = core.objectInfo(grid);
if (info.vertices !== 16 || core.objectList().length !== 1) throw new Error("a failed call left a trace");
print("script errors: ok (" + checked + " errors checked)");
