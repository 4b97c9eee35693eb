// multirescloth.simulate's argument checking: every mistake is a catchable
// Error naming the option and what it expected, and a failed call leaves
// nothing behind. Arguments: <tests/data> <shared data> <tmp>.
"use strict";
const [dataDir, , tmpDir] = core.scriptArguments();

core.include("test_asserts.js");

core.makePath(tmpDir);
const grid = core.loadObject(dataDir + "/grid3x3.obj");
const sim = options => () => multirescloth.simulate(grid, options);

// The object and the options object.
expectThrows(() => multirescloth.simulate(99), "ArgumentError", "multirescloth.simulate: no object with id 99");
expectThrows(() => multirescloth.simulate(grid, 5), "ArgumentError", "options must be an object, got the number 5");
expectThrows(sim({frame: 10}), "ArgumentError", "multirescloth.simulate: ", "unknown option 'frame'",
             "accepted: frames, fps, substeps, iterations, newtonCg, limiterSweeps, limiterAcceleration, limiterMassExponent, tNodeSag, pinsYield, collisionRounds, contactSlack, material, alpha, alphaBend, bendModel, " +
             "gravity, pins, colliders, " +
             "output, objSequence, updateObject, selfContact, threads");

// Scalars: wrong types and ranges name the option.
expectThrows(sim({frames: "10"}), "ArgumentError", "option 'frames' must be an integer, got the string \"10\"");
expectThrows(sim({frames: 0}), "ArgumentError", "option 'frames' must be an integer >= 1, got 0");
expectThrows(sim({frames: 2.5}), "ArgumentError", "option 'frames' must be an integer, got the number 2.5");
expectThrows(sim({fps: 0}), "ArgumentError", "option 'fps' must be from 0.001 to 100000 frames per second, got the number 0");
expectThrows(sim({fps: "30"}), "ArgumentError", "option 'fps' must be a finite number");
expectThrows(sim({fps: 1e-300}), "ArgumentError", "option 'fps' must be from 0.001 to 100000 frames per second, got the number 1e-300");
expectThrows(sim({fps: 1e300}), "ArgumentError", "option 'fps' must be from 0.001 to 100000 frames per second, got the number 1e+300");
expectThrows(sim({substeps: 0}), "ArgumentError", "option 'substeps' must be an integer from 1 to 1000, got the number 0");
expectThrows(sim({iterations: -1}), "ArgumentError", "option 'iterations' must be an integer from 1 to 100, got the number -1");
expectThrows(sim({bendModel: "hinge"}), "ArgumentError", "option 'bendModel'");
expectThrows(sim({newtonCg: -1}), "ArgumentError", "option 'newtonCg' must be an integer from 0 to 1000, got the number -1");
expectThrows(sim({limiterSweeps: -1}), "ArgumentError", "option 'limiterSweeps' must be an integer from 0 to 1000, got the number -1");
expectThrows(sim({limiterAcceleration: -0.1}), "ArgumentError", "option 'limiterAcceleration' must be a number >= 0, got the number -0.1");
expectThrows(sim({limiterAcceleration: 1}), "ArgumentError", "option 'limiterAcceleration' must be \"auto\" or a number >= 0 and < 1 (0: plain limiter sweeps), got 1");
expectThrows(sim({limiterMassExponent: -0.5}), "ArgumentError", "option 'limiterMassExponent' must be a number >= 0, got the number -0.5");
expectThrows(sim({limiterMassExponent: 1.5}), "ArgumentError", "option 'limiterMassExponent' must be a number >= 0 and <= 1 (1: mass-weighted limiter projections), got 1.5");
expectThrows(sim({collisionRounds: 0}), "ArgumentError", "option 'collisionRounds' must be an integer from 1 to 100, got the number 0");
expectThrows(sim({collisionRounds: 1.5}), "ArgumentError", "option 'collisionRounds' must be an integer, got the number 1.5");
expectThrows(sim({contactSlack: -0.001}), "ArgumentError", "option 'contactSlack' must be a number >= 0, got the number -0.001");
expectThrows(sim({contactSlack: "1mm"}), "ArgumentError", "option 'contactSlack'");
expectThrows(sim({threads: -1}), "ArgumentError", "option 'threads' must be an integer from 0 to 1024, got the number -1");
expectThrows(sim({threads: 2.5}), "ArgumentError", "option 'threads' must be an integer, got the number 2.5");
expectThrows(sim({alpha: NaN}), "ArgumentError", "option 'alpha' must be a finite number");
expectThrows(sim({alphaBend: "1"}), "ArgumentError", "option 'alphaBend' must be a finite number");
expectThrows(sim({selfContact: 0.05}), "ArgumentError",
             "option 'selfContact' must be false or a thickness from 0 to 0.02 m, got the number 0.05");
expectThrows(sim({selfContact: -0.001}), "ArgumentError", "option 'selfContact' must be false or a thickness");
expectThrows(sim({selfContact: true}), "ArgumentError", "option 'selfContact' must be false or a thickness", "got true");
expectThrows(sim({selfContact: "on"}), "ArgumentError", "option 'selfContact'");
expectThrows(sim({selfContact: {neighbourhood: 0.02}}), "ArgumentError", "missing option 'selfContact.thickness'");
expectThrows(sim({selfContact: {thickness: 0.05}}), "ArgumentError",
             "option 'selfContact.thickness' must be false or a thickness from 0 to 0.02 m, got the number 0.05");
expectThrows(sim({selfContact: {thickness: 0.003, neighbourhood: -1}}), "ArgumentError",
             "option 'selfContact.neighbourhood' must be a number >= 0");
expectThrows(sim({selfContact: {thickness: 0.003, neighbourhood: 0.5}}), "ArgumentError",
             "option 'selfContact.neighbourhood' must be at most 0.1 m, got 0.5");
expectThrows(sim({selfContact: {thickness: 0.003, radius: 1}}), "ArgumentError",
             "unknown option 'radius' in option 'selfContact'", "thickness, neighbourhood");
expectThrows(sim({gravity: [0, -9.81]}), "ArgumentError", "option 'gravity' must be an array of 3 numbers");
expectThrows(sim({updateObject: 1}), "ArgumentError", "option 'updateObject' must be true or false, got the number 1");
expectThrows(sim({tNodeSag: "yes"}), "ArgumentError", "option 'tNodeSag' must be true or false");
expectThrows(sim({pinsYield: "no"}), "ArgumentError", "option 'pinsYield' must be true or false");

// Material.
expectThrows(sim({material: "wool"}), "ArgumentError",
             "option 'material' must be one of \"cotton\", \"denim\", \"silk\", got the string \"wool\"");
expectThrows(sim({material: 3}), "ArgumentError", "option 'material' must be a preset name", "got the number 3");
expectThrows(sim({material: {preset: "denim", dampin: 1}}), "ArgumentError", "unknown option 'dampin' in option 'material'",
             "accepted: preset, arealDensity, stretchStiffness, shearStiffness, bendStiffness, damping, stretchLimit");
expectThrows(sim({material: {preset: "tweed"}}), "ArgumentError", "option 'material.preset' must be one of");
expectThrows(sim({material: {arealDensity: 0}}), "ArgumentError", "option 'material.arealDensity' must be a number > 0");
expectThrows(sim({material: {bendStiffness: -1}}), "ArgumentError", "option 'material.bendStiffness' must be a number >= 0");
expectThrows(sim({material: {stretchStiffness: "stiff"}}), "ArgumentError",
             "option 'material.stretchStiffness' must be a finite number");

// Colliders.
expectThrows(sim({colliders: [{type: "box", center: [0, 0, 0]}]}), "ArgumentError",
             "option 'colliders[0].type' must be one of \"plane\", \"sphere\", \"capsule\", got the string \"box\"");
expectThrows(sim({colliders: [{center: [0, 0, 0], radius: 1}]}), "ArgumentError", "missing option 'colliders[0].type'");
expectThrows(sim({colliders: {type: "plane"}}), "ArgumentError", "option 'colliders' must be an array");
expectThrows(sim({colliders: [{type: "plane"}, {type: "sphere", center: [0, 0, 0], radius: 0.1, thickness: 4}]}),
             "ArgumentError", "option 'colliders[1].thickness' must be from 0 to 0.05 m, got the number 4");
expectThrows(sim({colliders: [{type: "plane"}, {type: "sphere", center: [0, 0, 0]}]}), "ArgumentError",
             "missing option 'colliders[1].radius'", "accepted: type, center, radius, thickness, friction");
expectThrows(sim({colliders: [{type: "plane", radius: 1}]}), "ArgumentError",
             "unknown option 'radius' in option 'colliders[0]'", "accepted: type, point, normal, thickness, friction");
expectThrows(sim({colliders: [{type: "sphere", center: [0, 0, 0], radius: -1}]}), "ArgumentError",
             "option 'colliders[0].radius' must be a number > 0, got the number -1");
expectThrows(sim({colliders: [{type: "sphere", center: [0, 0], radius: 1}]}), "ArgumentError",
             "option 'colliders[0].center' must be an array of 3 numbers");
expectThrows(sim({colliders: [{type: "capsule", a: [0, 0, 0], b: [0, 1, 0], radius: 0.1, radiusA: 0.2}]}),
             "ArgumentError", "option 'colliders[0]': give either 'radius' or 'radiusA' and 'radiusB'");
expectThrows(sim({colliders: [{type: "capsule", a: [0, 0, 0], b: [0, 1, 0], radiusA: 0.2}]}), "ArgumentError",
             "missing option 'colliders[0].radiusB'");
expectThrows(sim({colliders: [{type: "capsule", a: [0, 0, 0], b: [0, 1, 0], radiusA: 0, radiusB: 0}]}),
             "ArgumentError", "option 'colliders': collider 0 (capsule)");
expectThrows(sim({colliders: [{type: "plane", normal: [0, 0, 0]}]}), "ArgumentError",
             "option 'colliders': collider 0 (plane)", "normal");
expectThrows(sim({colliders: [{type: "sphere", center: [0, 0, 0], radius: 1, friction: -0.1}]}), "ArgumentError",
             "option 'colliders[0].friction' must be a number >= 0");
expectThrows(sim({colliders: [{type: "sphere", center: [0, 0, 0], radius: 1, thickness: "thin"}]}), "ArgumentError",
             "option 'colliders[0].thickness' must be a finite number");

// Pins: loop names that do not exist, ids out of range, hanging vertices.
expectThrows(sim({pins: "loop:9"}), "ArgumentError", "option 'pins': ", "loop:9", "the mesh has 1 boundary loop");
expectThrows(sim({pins: "middle"}), "ArgumentError", "option 'pins': ", "middle");
expectThrows(sim({pins: ["top", "loop:1"]}), "ArgumentError", "option 'pins[1]': ", "loop:1");
expectThrows(sim({pins: 5}), "ArgumentError", "option 'pins' must be a boundary loop name", "got the number 5");
expectThrows(sim({pins: [0, {}]}), "ArgumentError", "option 'pins[1]' must be a vertex id or a boundary loop name");
expectThrows(sim({pins: [0, 1.5]}), "ArgumentError", "option 'pins[1]' must be an integer, got the number 1.5");
expectThrows(sim({pins: [16]}), "ArgumentError", "multirescloth.simulate: ", "pinned vertex 16 is out of range");
// The adaptively refined grid of adaptive_grid_test.js has exactly 16 T-nodes;
// pinning any of them is refused, pinning any other vertex is fine.
multirescloth.setModes(grid, [5, 6, 9, 10], 3);
const refined = multirescloth.refineAdaptive(grid, {delta: 8, maxLevel: 3, balance: true});
const info = core.objectInfo(refined);
const refused = [];
for (let vertex = 0; vertex < info.vertices; ++vertex) {
  try {
    multirescloth.simulate(refined, {frames: 1, pins: [vertex]});
  } catch (error) {
    if (!(error.name === "ArgumentError" && error.message.includes("pinned vertex " + vertex + " is a hanging node")))
      throw new Error("pinning vertex " + vertex + ": unexpected " + error.name + ": " + error.message);
    refused.push(vertex);
  }
}
expectEqual(refused.length, info.hangingNodes, "every hanging vertex (and only those) refused as a pin");
expectThrows(() => multirescloth.simulate(refined, {pins: [0, refused[0]]}), "ArgumentError",
             "pinned vertex " + refused[0] + " is a hanging node", "pin its parents instead");

// Output folders must exist; nothing is written by a failed call.
expectThrows(sim({output: tmpDir + "/no_such_folder/cache.pc2"}), "OutputError",
             "option 'output': folder", "no_such_folder", "does not exist");
expectThrows(sim({objSequence: tmpDir + "/no_such_folder/frame"}), "OutputError", "option 'objSequence': folder");
expectThrows(sim({output: tmpDir}), "OutputError", "option 'output': ", "is a folder");
core.writeTextFile(tmpDir + "/plain.obj", "not a folder\n");
expectThrows(sim({output: tmpDir + "/plain.obj/cache.pc2"}), "OutputError", "option 'output': ", "plain.obj' is a file, not a folder");
expectThrows(sim({output: ""}), "ArgumentError", "option 'output' must be a non-empty string");
const cache = tmpDir + "/never.pc2";
expectThrows(sim({output: cache, frames: 2, colliders: [{type: "sphere", center: [0, 0, 0], radius: 0}]}),
             "ArgumentError", "colliders[0].radius");
if (core.fileExists(cache)) throw new Error("a failed call wrote " + cache);
expectThrows(() => core.fileSize(cache), "InputError", "core.fileSize: ", "never.pc2: no such file");
expectThrows(() => core.fileSize(tmpDir), "InputError", "core.fileSize: ", "not a file");
expectThrows(() => core.filesEqual(dataDir + "/grid3x3.obj", cache), "InputError", "core.filesEqual: ", "never.pc2");

// Outputs that would overwrite each other, and a cache named like a mesh.
expectThrows(sim({output: tmpDir + "/cache.obj"}), "ArgumentError",
             "option 'output' must be the PC2 cache (e.g. walk.pc2), not an .obj");
expectThrows(sim({output: tmpDir + "/clash_0000.pc2", objSequence: tmpDir + "/clash", frames: 2}), "ArgumentError",
             "the rest mesh beside option 'output' is frame 0 of option 'objSequence'");
expectEqual(core.fileExists(tmpDir + "/clash_0000.obj"), false, "nothing written by the refused call");
// An output that is one of the run's inputs (its rest mesh replaced the
// garment's file), and one that is a folder (found after the run had
// written its cache), are refused before the run.
core.writeTextFile(tmpDir + "/source.obj", core.readTextFile(dataDir + "/grid3x3.obj"));
const source = core.loadObject(tmpDir + "/source.obj");
expectThrows(() => multirescloth.simulate(source, {frames: 1, output: tmpDir + "/source.pc2"}), "OutputError",
             "the rest mesh beside option 'output' is the garment's file", "source.obj",
             "expected outputs that leave the run's inputs as they are");
expectEqual(core.fileExists(tmpDir + "/source.pc2"), false, "no cache written by the refused call");
core.makePath(tmpDir + "/folder.obj");
expectThrows(sim({frames: 1, output: tmpDir + "/folder.pc2"}), "OutputError",
             "the rest mesh beside option 'output', ", "folder.obj, is a folder");
expectEqual(core.fileExists(tmpDir + "/folder.pc2"), false, "no cache written by the refused call");
// The OBJ sequence too: a frame of it that is the garment's file, or a folder.
core.writeTextFile(tmpDir + "/seq_0001.obj", core.readTextFile(dataDir + "/grid3x3.obj"));
const frameSource = core.loadObject(tmpDir + "/seq_0001.obj");
expectThrows(() => multirescloth.simulate(frameSource, {frames: 2, objSequence: tmpDir + "/seq"}), "OutputError",
             "frame 1 of option 'objSequence' is the garment's file", "seq_0001.obj",
             "expected outputs that leave the run's inputs as they are");
expectEqual(core.fileExists(tmpDir + "/seq_0000.obj"), false, "no frame written by the refused call");
core.deleteObject(frameSource);
core.makePath(tmpDir + "/seqdir_0000.obj");
expectThrows(sim({frames: 1, objSequence: tmpDir + "/seqdir"}), "OutputError",
             "frame 0 of option 'objSequence', ", "seqdir_0000.obj, is a folder; expected a file's path");
core.deleteObject(source);
// A frame's work is bounded: progress and Ctrl-C come between frames.
expectThrows(sim({substeps: 1e9}), "ArgumentError", "option 'substeps' must be an integer from 1 to 1000, got the number 1e+09");
expectThrows(sim({iterations: 101}), "ArgumentError", "option 'iterations' must be an integer from 1 to 100, got the number 101");
expectThrows(sim({limiterSweeps: 60000}), "ArgumentError", "option 'limiterSweeps' must be an integer from 0 to 1000, got the number 60000");
expectThrows(sim({collisionRounds: 101}), "ArgumentError", "option 'collisionRounds' must be an integer from 1 to 100, got the number 101");
expectThrows(sim({threads: 1e9}), "ArgumentError", "option 'threads' must be an integer from 0 to 1024, got the number 1e+09");
expectThrows(sim({newtonCg: 1e9}), "ArgumentError", "option 'newtonCg' must be an integer from 0 to 1000, got the number 1e+09");

// The script carries on; the objects are as they were.
expectEqual(core.objectList().length, 2, "no objects added by failed calls");
expectEqual(multirescloth.simulate(grid, {frames: 1}).frames, 1, "a good call after the failures");
print("simulate errors: ok (" + checked + " errors checked)");
