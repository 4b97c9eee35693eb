// The character options of multirescloth.simulate and recordInstance: every
// mistake is a catchable Error naming the option, and a failed call writes
// nothing. Arguments: <tests/data> <shared data> <tmp>.
"use strict";
const [dataDir, , tmpDir] = core.scriptArguments();

core.include("test_asserts.js");

core.makePath(tmpDir);
const walk = core.resourcePath() + "/characters/walk_instance.bvh";
if (!core.fileExists(walk)) throw new Error("the embedded character is missing: " + walk);
const skirt = core.loadObject(core.resourcePath() + "/garments/default_skirt.obj");
const grid = core.loadObject(dataDir + "/grid3x3.obj");
const sim = options => () => multirescloth.simulate(skirt, options);
const record = options => () => multirescloth.recordInstance(skirt, options);
const missing = tmpDir + "/no_such_motion.bvh";

// The body.
expectThrows(sim({motion: walk, body: "robot"}), "ArgumentError", "multirescloth.simulate: ",
             "option 'body' must be one of \"capsules\", \"mesh\", got the string \"robot\"");
expectThrows(sim({motion: walk, body: {type: "robot"}}), "ArgumentError",
             "option 'body.type' must be one of \"capsules\", \"mesh\"");
expectThrows(sim({motion: walk, body: "mesh"}), "ArgumentError", "option 'body': \"mesh\" needs the MakeHuman files",
             "obj, skeleton, weights");
expectThrows(sim({motion: walk, body: {type: "mesh"}}), "ArgumentError",
             "option 'body': type \"mesh\" needs the MakeHuman files", "missing: obj, skeleton, weights");
expectThrows(sim({motion: walk, body: {type: "mesh", obj: walk, skeleton: walk}}), "ArgumentError",
             "option 'body'", "missing: weights");
expectThrows(sim({motion: walk, body: {type: "capsules", obj: walk}}), "ArgumentError",
             "option 'body': give all three MakeHuman files", "missing: skeleton, weights");
expectThrows(sim({motion: walk, body: {type: "mesh", obj: missing, skeleton: walk, weights: walk}}), "InputError",
             "option 'body.obj': ", "no_such_motion.bvh: no such file");
expectThrows(sim({motion: walk, body: {radius: 1}}), "ArgumentError", "unknown option 'radius' in option 'body'",
             "accepted: type, obj, skeleton, weights, units, thickness, friction");
expectThrows(sim({motion: walk, body: {units: "cm"}}), "ArgumentError",
             "option 'body.units' are the units of the MakeHuman body file (obj): give obj, skeleton and weights with it");
expectThrows(sim({motion: walk, body: {obj: walk, skeleton: walk, weights: walk, units: "cmu"}}), "ArgumentError",
             "option 'body.units' must be one of \"m\", \"dm\", \"cm\", \"mm\", \"inch\", got the string \"cmu\"");
expectThrows(sim({motion: walk, body: {thickness: -1}}), "ArgumentError",
             "option 'body.thickness' must be from 0 to 0.05 m, got the number -1");
// A thickness in millimetres read as metres pushes the cloth metres out at the first step.
expectThrows(sim({motion: walk, body: {thickness: 4}}), "ArgumentError",
             "option 'body.thickness' must be from 0 to 0.05 m, got the number 4");
expectThrows(sim({motion: walk, body: 3}), "ArgumentError", "option 'body' must be \"capsules\", \"mesh\" or an object");
// Capsule radii, per joint: a radius or [head, tail] in metres.
expectThrows(sim({motion: walk, body: {radii: {LeftUpLeg: -0.1}}}), "ArgumentError",
             "option 'body.radii.LeftUpLeg' must be >= 0 (0 removes the capsule), got the number -0.1");
expectThrows(sim({motion: walk, body: {radii: {LeftUpLeg: [0.1]}}}), "ArgumentError",
             "option 'body.radii.LeftUpLeg' must be a radius or [head, tail] in metres");
expectThrows(sim({motion: walk, body: {radii: {LeftUpLeg: [0.1, "wide"]}}}), "ArgumentError",
             "option 'body.radii.LeftUpLeg[1]' must be a finite number, got the string \"wide\"");
expectThrows(sim({motion: walk, body: {radii: [0.1, 0.2]}}), "ArgumentError",
             "option 'body.radii' must be an object {joint name: radius or [head, tail]}");
expectThrows(sim({motion: walk, body: {type: "mesh", obj: walk, skeleton: walk, weights: walk, radii: {Hips: 0.1}}}),
             "ArgumentError", "option 'body.radii' applies to capsules only, not to type \"mesh\"");
expectThrows(sim({motion: {path: walk, units: "m"}, body: {radii: {Tail: 0.05}}, frames: 1}), "ArgumentError",
             "option 'body.radii.Tail': the motion's skeleton has no joint of that name");

expectThrows(sim({motion: walk, body: {waistFollows: "skin"}}), "ArgumentError",
             "option 'body.waistFollows' \"skin\" needs a body to skin by");
expectThrows(sim({motion: walk, body: {waistFollows: "ribs"}}), "ArgumentError", "option 'body.waistFollows'");
expectThrows(sim({motion: walk, body: {waistSmoothing: -0.01}}), "ArgumentError",
             "option 'body.waistSmoothing' must be a number >= 0");
expectThrows(sim({motion: walk, body: {waistSmoothing: 0.02}}), "ArgumentError",
             "option 'body.waistSmoothing' applies where the waist follows the skin");
expectThrows(sim({motion: walk, body: {obj: walk, skeleton: walk, weights: walk, waistFollows: "pelvis", waistSmoothing: 0}}),
             "ArgumentError", "option 'body.waistSmoothing' applies where the waist follows the skin");
expectThrows(sim({motion: walk, body: {legBridges: 3}}), "ArgumentError",
             "option 'body.legBridges' must be \"auto\", false, 0 or a reach from 0.5 to 2 bones below the hips",
             "got the number 3");
expectThrows(sim({motion: walk, body: {legBridges: 0.2}}), "ArgumentError", "option 'body.legBridges'", "got the number 0.2");
expectThrows(sim({motion: walk, body: {legBridges: "knees"}}), "ArgumentError", "option 'body.legBridges'");
// Bridges join a capsule on each leg: a thigh without one (radius 0) leaves
// them nothing to join, unless there are none.
expectThrows(() => multirescloth.simulate(skirt, {motion: {path: walk, units: "m"}, place: "firstFrame", preroll: 0.1,
                                                  frames: 1, body: {type: "capsules", radii: {LeftUpLeg: 0}}}),
             "ArgumentError", "option 'body': leg bridges need a capsule on both thighs", "or no leg bridges");
expectEqual(multirescloth.simulate(skirt, {motion: {path: walk, units: "m"}, place: "firstFrame", preroll: 0.1, frames: 1,
                                           body: {type: "capsules", radii: {LeftUpLeg: 0}, legBridges: false}}).legBridges,
            0, "a thigh without a capsule and no bridges");
expectThrows(sim({motion: walk, body: {armClearance: 0.5}}), "ArgumentError",
             "option 'body.armClearance' must be \"auto\", false or a clearance from 0 to 0.1 m, got the number 0.5");
expectThrows(sim({motion: walk, body: {armClearance: -0.01}}), "ArgumentError", "option 'body.armClearance'");
expectThrows(sim({motion: walk, body: {armClearance: "wide"}}), "ArgumentError", "option 'body.armClearance'");
expectThrows(sim({motion: walk, body: {handMittens: "yes"}}), "ArgumentError", "option 'body.handMittens'");
expectThrows(sim({motion: walk, body: {handMittens: false}}), "ArgumentError",
             "option 'body.handMittens' applies to type \"mesh\" (the capsule body has no hands to replace)");

// The motion.
expectThrows(sim({motion: missing}), "InputError", "option 'motion': ", "no_such_motion.bvh: no such file");
expectThrows(sim({motion: {path: missing, units: "cmu"}}), "InputError", "option 'motion.path': ", "no such file");
expectThrows(sim({motion: dataDir + "/grid3x3.obj"}), "InputError", "option 'motion': ", "grid3x3.obj");
expectThrows(sim({motion: {path: walk, units: "feet"}}), "ArgumentError",
             "option 'motion.units' must be one of \"m\", \"cmu\", \"dm\", \"cm\", \"mm\", \"inch\", \"auto\", got the string \"feet\"");
// A figure too small or big for its units (the embedded walks are in metres).
expectThrows(sim({motion: {path: walk, units: "cm"}}), "InputError", "multirescloth.simulate: option 'motion': ",
             "walk_instance.bvh read in units 'cm' (0.01 m per unit): the figure's legs are 0.01 m long (hip to ankle in "
             + "its rest pose), 0.01 times an adult's 0.79 m; expected 0.4-2 times: check the units; in 'm' they are "
             + "0.79 m (units \"auto\" picks that)");
expectThrows(sim({motion: {path: walk, scale: 100}}), "InputError",
             "walk_instance.bvh read at scale 100 m per unit: the figure's legs are 79.01 m long",
             "in 'm' they are 0.79 m");
expectThrows(record({motion: {path: walk, units: "mm"}, output: tmpDir + "/x.pc2"}), "InputError",
             "multirescloth.recordInstance: option 'motion': ", "read in units 'mm'");
expectThrows(() => multirescloth.motionInfo({path: walk, units: "dm"}), "InputError",
             "multirescloth.motionInfo: option 'motion': ", "read in units 'dm' (0.1 m per unit)", "in 'm' they are 0.79 m");
expectThrows(() => multirescloth.motionInfo({path: walk, fps: 30}), "ArgumentError", "unknown option 'fps' in option 'motion'");
expectThrows(() => multirescloth.motionInfo(missing), "InputError", "option 'motion': ", "no such file");
expectThrows(() => multirescloth.motionInfo({path: dataDir + "/grid3x3.obj", units: "auto"}), "InputError",
             "option 'motion': ", "grid3x3.obj");
expectThrows(sim({motion: {path: walk, units: "m", scale: 1}}), "ArgumentError",
             "option 'motion': give either 'units' or 'scale', not both");
expectThrows(sim({motion: {path: walk, scale: 0}}), "ArgumentError", "option 'motion.scale' must be a number > 0");
expectThrows(sim({motion: {units: "m"}}), "ArgumentError", "missing option 'motion.path'");
expectThrows(sim({motion: {path: walk, start: -1}}), "ArgumentError", "option 'motion.start' must be a number >= 0");
expectThrows(sim({motion: {path: walk, start: 1000}}), "ArgumentError",
             "option 'motion.start' must be at most the clip's length");
expectThrows(sim({motion: {path: walk, skipFirst: true}, skipFirst: true}), "ArgumentError",
             "give 'skipFirst' either in option 'motion' or at the top level");
expectThrows(sim({motion: {path: walk, fps: 30}}), "ArgumentError", "unknown option 'fps' in option 'motion'");
expectThrows(sim({motion: 7}), "ArgumentError", "option 'motion' must be a BVH file path or an object");

// The waist, the placement and the rates.
expectThrows(sim({motion: walk, waist: "top", pins: "top"}), "ArgumentError",
             "give the pinned waist as option 'waist' or option 'pins', not both");
expectThrows(sim({motion: walk, waist: "loop:5"}), "ArgumentError", "option 'waist': ", "loop:5");
expectThrows(sim({motion: walk, waist: ["top", {}]}), "ArgumentError", "option 'waist[1]' must be a vertex id");
expectThrows(sim({motion: walk, place: "makehuman"}), "ArgumentError", "option 'place': \"makehuman\"",
             "option 'body' must give the MakeHuman files");
expectThrows(sim({motion: walk, place: "origin"}), "ArgumentError",
             "option 'place' must be one of \"none\", \"makehuman\", \"firstFrame\"");
expectThrows(sim({motion: walk, preroll: -0.5}), "ArgumentError", "option 'preroll' must be a number >= 0");
expectThrows(sim({motion: walk, stepRate: 20}), "ArgumentError", "option 'stepRate' must be at least option 'fps'");
expectThrows(sim({motion: walk, fps: 200}), "ArgumentError", "option 'stepRate' must be at least option 'fps' (200",
             "got 120 (its default: give a step rate of at least 200)");
// A frame's work is bounded (progress and Ctrl-C come between frames); a
// step rate of 1e300 also rounded to a count beyond int, and ran one a frame.
expectThrows(sim({motion: walk, stepRate: 3e10}), "ArgumentError",
             "option 'stepRate' must be at most 1000 steps per output frame (1000 x option 'fps' = 30000), got 3e+10");
expectThrows(sim({motion: walk, stepRate: 1e300}), "ArgumentError", "option 'stepRate' must be at most 1000 steps");
expectThrows(sim({motion: walk, substeps: 4}), "ArgumentError", "option 'substeps' does not apply with option 'motion'",
             "stepRate");

// A step rate that is no whole number of steps per output frame is
// rounded to one, and said so before the run (120 at 90 fps ran at 90).
{
  const report = multirescloth.simulate(skirt, {motion: walk, body: "capsules", place: "firstFrame", fps: 90,
                                                stepRate: 120, preroll: 0.1, frames: 1});
  expectEqual(report.stepRate, 90, "the rate run: one step a frame");
  expectEqual(report.warnings.some(w => w.includes("option 'stepRate' 120 is no whole number of steps per output frame " +
                                                   "at 90 fps: the run takes 1 a frame, 90 steps per second")),
              true, "the warning names the rate run: " + JSON.stringify(report.warnings));
  const whole = multirescloth.simulate(skirt, {motion: walk, body: "capsules", place: "firstFrame", fps: 30,
                                               stepRate: 120, preroll: 0.1, frames: 1});
  expectEqual(whole.warnings.some(w => w.includes("stepRate")), false, "no warning at a multiple of fps");
  // A tool that takes the options under its own names has its warnings use them.
  const named = multirescloth.simulate(skirt, {motion: walk, body: "capsules", place: "firstFrame", fps: 90,
                                               stepRate: 120, preroll: 0.1, frames: 1,
                                               optionNames: {stepRate: "--step-rate", fps: "--fps"}});
  expectEqual(named.warnings.some(w => w.includes("simulate: --step-rate 120 is no whole number of steps per output " +
                                                  "frame at 90 fps") && w.includes("a multiple of --fps keeps")),
              true, "the warning in the tool's names: " + JSON.stringify(named.warnings));
  expectThrows(sim({optionNames: {stepRat: "--step-rate"}}), "ArgumentError", "unknown option 'stepRat' in option 'optionNames'");
  expectThrows(sim({optionNames: {stepRate: 3}}), "ArgumentError", "optionNames.stepRate");
}

// Character options without a motion.
for (const [key, value] of [["body", "capsules"], ["place", "makehuman"], ["waist", "top"], ["preroll", 1],
                            ["stepRate", 240], ["skipFirst", false]])
  expectThrows(sim({[key]: value}), "ArgumentError", "option '" + key + "' needs option 'motion'");
expectThrows(sim({motions: walk}), "ArgumentError", "unknown option 'motions'",
             "updateObject, selfContact, threads, motion, body, place, waist, preroll, stepRate, skipFirst");

// recordInstance: motion and output are required; the cache is not an OBJ.
expectThrows(record({output: tmpDir + "/x.pc2"}), "ArgumentError", "multirescloth.recordInstance: ",
             "missing option 'motion'");
expectThrows(record({motion: walk}), "ArgumentError", "multirescloth.recordInstance: ", "missing option 'output'");
expectThrows(record({motion: walk, output: tmpDir + "/x.obj"}), "ArgumentError", "option 'output' must be the PC2 cache");
expectThrows(record({motion: walk, output: tmpDir + "/no_such_folder/x.pc2"}), "OutputError",
             "option 'output': folder");
expectThrows(record({motion: walk, frame: 3, output: tmpDir + "/x.pc2"}), "ArgumentError",
             "unknown option 'frame' in recordInstance options");
expectThrows(() => multirescloth.recordInstance(skirt), "ArgumentError", "missing option 'motion'");
expectThrows(() => multirescloth.recordInstance(99, {}), "ArgumentError", "no object with id 99");
// A grid has no waist to speak of, but its highest loop is pinned all the same;
// a hanging-node or out-of-range waist id is refused by the model.
expectThrows(() => multirescloth.recordInstance(grid, {motion: walk, waist: [99], output: tmpDir + "/grid.pc2"}),
             "ArgumentError", "pinned vertex 99 is out of range");

// "auto" needs legs to measure; a clip without them is read as given.
const legless = tmpDir + "/legless.bvh";
core.writeTextFile(legless, "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n CHANNELS 3 Xposition Yposition Zposition\n" +
                            " End Site\n {\n  OFFSET 0 10 0\n }\n}\nMOTION\nFrames: 2\nFrame Time: 0.1\n0 0 0\n0 0 1\n");
expectThrows(() => multirescloth.motionInfo({path: legless, units: "auto"}), "InputError", "option 'motion': ",
             "legless.bvh has no legs to measure (LeftUpLeg to LeftFoot, RightUpLeg to RightFoot, after renaming), so "
             + "units \"auto\" cannot choose; give the units");
expectEqual([multirescloth.motionInfo({path: legless, units: "cm"}).legs, multirescloth.motionInfo(legless).frames],
            [0, 2], "a clip without legs, units given");
// Nor can "auto" axes tell which way it stands: it is read as it is, and says why.
expectEqual([multirescloth.motionInfo(legless).axesTurned, multirescloth.motionInfo(legless).axesUndecided],
            ["", "it has no Head, Neck or Spine by CMU names"], "a clip whose way up is unknown");
expectEqual(multirescloth.motionInfo({path: legless, axes: "asIs"}).axesUndecided, "", "axes asIs: nothing to decide");
// A skeleton collapsed to one point (every OFFSET 0) has legs of length 0: refused.
const collapsed = tmpDir + "/collapsed.bvh";
core.writeTextFile(collapsed, core.readTextFile(walk).replace(/OFFSET [-0-9. ]+/g, "OFFSET 0 0 0"));
expectThrows(() => multirescloth.motionInfo(collapsed), "InputError", "collapsed.bvh read in units 'm'",
             "the figure's legs are 0.00 m long");
expectThrows(() => multirescloth.motionInfo({path: collapsed, units: "auto"}), "InputError",
             "collapsed.bvh has legs of length 0 (its rest pose puts hip and ankle at one point)");
// A garment loaded in the wrong units is refused on a character, before the run.
const tiny = core.loadObject(core.resourcePath() + "/garments/default_skirt.obj", {units: "cm"});
expectThrows(() => multirescloth.simulate(tiny, {motion: walk, frames: 1}), "InputError",
             "the garment spans 0.00", "expected 0.1-4 m for a garment worn by a person: check the units");
// A pre-roll is a second or two: 1e8 s overflowed its frame count and was skipped.
expectThrows(() => multirescloth.simulate(skirt, {motion: walk, frames: 1, preroll: 1e8}), "ArgumentError",
             "option 'preroll' must be 0 or a number of seconds from 0.001 to 60, got 1e+08");
expectThrows(sim({motion: walk, preroll: 1e-300}), "ArgumentError",
             "option 'preroll' must be 0 or a number of seconds from 0.001 to 60, got 1e-300");
// The body's cache on the garment's: refused before the run.
expectThrows(() => multirescloth.recordInstance(skirt, {motion: walk, frames: 1, preroll: 0, output: tmpDir + "/same.pc2",
                                                        bodyOutput: tmpDir + "/same.pc2"}),
             "ArgumentError", "option 'output' and option 'bodyOutput' are one file");
expectThrows(() => multirescloth.recordInstance(skirt, {motion: walk, frames: 1, preroll: 0, output: tmpDir + "/cloth.pc2",
                                                        bodyOutput: tmpDir + "/body.obj"}),
             "ArgumentError", "option 'bodyOutput' must be the body's PC2 cache (e.g. body.pc2), not an .obj",
             "got \"" + tmpDir + "/body.obj\"");
// A clip without Hips: the message suggests the joint that says hips.
const hipless = tmpDir + "/hipless.bvh";
core.writeTextFile(hipless, core.readTextFile(walk).replace("ROOT Hips", "ROOT Armature\n{\n OFFSET 0 0 0\n CHANNELS 0\n JOINT my_hips"
                                                            ).replace(/\nMOTION/, "}\nMOTION"));
expectThrows(() => multirescloth.simulate(skirt, {motion: hipless, frames: 1}), "InputError", "hipless.bvh has no joint 'Hips'",
             "e.g. {\"my_hips\": \"Hips\"}");
// No joint says hips or pelvis: it suggests the first that carries the figure
// (position channels), not the channel-less wrapper above it.
const groin = tmpDir + "/groin.bvh";
core.writeTextFile(groin, core.readTextFile(walk).replace("ROOT Hips", "ROOT Armature\n{\n OFFSET 0 0 0\n CHANNELS 0\n JOINT Root")
                                                 .replace(/HipJoint/g, "Groin").replace(/\nMOTION/, "}\nMOTION"));
expectThrows(() => multirescloth.simulate(skirt, {motion: groin, frames: 1}), "InputError", "groin.bvh has no joint 'Hips'",
             "e.g. {\"Root\": \"Hips\"}");

// motionInfo: the clip as a run reads it, units "auto" resolved.
const info = multirescloth.motionInfo({path: walk, units: "auto"});
expectEqual([info.units, info.metresPerUnit, info.joints[0], info.axesTurned, Object.keys(info.jointsRenamed).length],
            ["auto: m", 1, "Hips", "", 0], "motionInfo of the embedded walk");
expectAtMost(Math.abs(info.legs - 0.790142), 1e-6, "the mannequin's legs (m)");
expectAtMost(Math.abs(info.legsFactor - 0.790142 / 0.79), 1e-6, "legs against an adult's");
expectAtMost(Math.abs(info.duration - (info.frames - 1) * info.frameTime), 1e-12, "duration");
const autoRun = multirescloth.simulate(skirt, {motion: {path: walk, units: "auto"}, frames: 1, preroll: 0});
expectEqual(autoRun.motionUnits, "auto: m", "a run's report says the units auto chose");

for (const file of ["x.pc2", "x.obj", "grid.pc2", "grid.obj"])
  if (core.fileExists(tmpDir + "/" + file)) throw new Error("a failed call wrote " + file);
print("character errors: ok (" + checked + " errors checked)");
