// The embedded skirt on the embedded squat: at the deepest knee bend the
// mannequin's thigh capsules rise into the front of the waist, which is
// pinned to the pelvis. By default (pinsYield) those pins are moved out
// onto the capsules' surface, off their targets, and simulate warns with
// how far (run_and_check); with pinsYield false they stay inside and
// simulate warns with how deep. Either way the report keeps the pins apart
// from the cloth, fitWarning false keeps the warning out of the log, and
// the walk, whose pins stay clear, runs without one.
"use strict";
core.include("test_asserts.js");
const skirt = core.loadObject(core.resourcePath() + "/garments/default_skirt.obj");
const run = (clip, frames, extra) => multirescloth.simulate(skirt, Object.assign({
  motion: {path: core.resourcePath() + "/characters/" + clip, units: "m"}, body: "capsules", place: "firstFrame",
  preroll: 1.0, frames: frames}, extra));
const describe = (r) => "maxPenetration " + (1000 * r.maxPenetration).toFixed(2) + " mm at " + JSON.stringify(r.deepest) +
    ", maxPinnedDepth " + (1000 * r.maxPinnedDepth).toFixed(2) + " mm, maxPinYield " + (1000 * r.maxPinYield).toFixed(2) +
    " mm, maxWaistError " + (1000 * r.maxWaistError).toFixed(2) + " mm, maxClothDepth " + (1000 * r.maxClothDepth).toFixed(2) +
    " mm, maxStretch " + (100 * r.maxStretch).toFixed(1) + " % (cloth " + (100 * r.maxClothStretch).toFixed(1) +
    " %), tear " + (1000 * r.maxTearOpening).toFixed(1) + " mm";

const yielded = run("squat.bvh", 60, {fitWarning: true});
print("squat, pins yielding: " + describe(yielded));
if (!(yielded.maxPinYield > 0.01)) throw new Error("maxPinYield " + yielded.maxPinYield + ": expected > 1 cm");
expectAtMost(yielded.maxPinnedDepth, 0.001, "the yielded pins' depth");
expectEqual(yielded.maxWaistError >= yielded.maxPinYield - 1e-9, true, "the waist error counts the yield");
expectAtMost(yielded.maxClothDepth, 0.002, "the cloth's own depth (issue 4: 2 mm)");
expectEqual(yielded.maxTearOpening, 0, "no edge doubled");

const kept = run("squat.bvh", 60, {fitWarning: true, pinsYield: false});
print("squat, pins kept on their targets: " + describe(kept));
expectEqual([kept.deepest.pinned, kept.maxPinYield], [true, 0], "the deepest vertex is a pin, which never moved");
if (!(kept.maxPinnedDepth > 0.01)) throw new Error("maxPinnedDepth " + kept.maxPinnedDepth + ": expected > 1 cm");
expectAtMost(kept.maxWaistError, 1e-9, "pins on their targets");
expectEqual(kept.maxDepth, Math.max(kept.maxPinnedDepth, kept.maxClothDepth), "maxDepth, the larger part");
expectAtMost(kept.maxClothDepth, 0.002, "the cloth's own depth (issue 4: 2 mm)");
if (!(kept.maxClothPenetration < kept.maxPenetration)) throw new Error("the cloth's penetration is not the pins'");

const quiet = run("squat.bvh", 60, {fitWarning: false});
expectEqual(quiet.maxPinYield, yielded.maxPinYield, "the quiet run's report");
const walk = run("walk_new.bvh", 30, {fitWarning: true});
expectEqual([walk.maxPinYield, walk.maxPinnedDepth], [0, 0], "the walk's pins");
expectAtMost(walk.maxWaistError, 1e-9, "the walk's waist on its targets");
print("pinned depth: ok");
