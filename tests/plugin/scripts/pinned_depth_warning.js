// The embedded skirt on the embedded squat: at the deepest knee bend the
// mannequin's thigh capsules rise into the front of the waist, which is
// pinned to the pelvis and so never pushed out. The report keeps the pins
// apart from the cloth (deepest.pinned, maxPinnedDepth, maxClothDepth) and
// simulate warns (run_and_check: once, naming the depth and the frame):
// not again with fitWarning false, which keeps it out of the log as it does
// the fit's; the walk's pins stay within the thickness and it runs without it.
"use strict";
core.include("test_asserts.js");
const skirt = core.loadObject(core.resourcePath() + "/garments/default_skirt.obj");
const run = (clip, frames, fitWarning) => multirescloth.simulate(skirt, {
  motion: {path: core.resourcePath() + "/characters/" + clip, units: "m"}, body: "capsules", place: "firstFrame",
  preroll: 1.0, frames: frames, fitWarning: fitWarning});
const squat = run("squat.bvh", 60, true);
print("squat: maxPenetration " + (1000 * squat.maxPenetration).toFixed(2) + " mm at " + JSON.stringify(squat.deepest) +
      ", maxPinnedDepth " + (1000 * squat.maxPinnedDepth).toFixed(2) + " mm, maxClothDepth " +
      (1000 * squat.maxClothDepth).toFixed(2) + " mm, maxClothPenetration " +
      (1000 * squat.maxClothPenetration).toFixed(2) + " mm");
expectEqual(squat.deepest.pinned, true, "the squat's deepest vertex is a pin");
if (!(squat.maxPinnedDepth > 0.01)) throw new Error("maxPinnedDepth " + squat.maxPinnedDepth + ": expected > 1 cm");
expectEqual(squat.maxDepth, Math.max(squat.maxPinnedDepth, squat.maxClothDepth), "maxDepth, the larger part");
expectAtMost(squat.maxClothDepth, 0.002, "the cloth's own depth (issue 4: 2 mm)");
if (!(squat.maxClothPenetration < squat.maxPenetration)) throw new Error("the cloth's penetration is not the pins'");
const quiet = run("squat.bvh", 60, false);
expectEqual(quiet.maxPinnedDepth, squat.maxPinnedDepth, "the quiet run's report");
const walk = run("walk_new.bvh", 30, true);
expectAtMost(walk.maxPinnedDepth, 0.001, "the walk's pins below the surface");
print("pinned depth: ok");
