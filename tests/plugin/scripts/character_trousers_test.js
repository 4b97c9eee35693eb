// The shared MakeHuman trousers (decimetres, modelled on base.obj) on two
// seconds of CMU 07_06 with each body kind: the skinned MakeHuman mesh, and
// capsules fitted to it. Both record a PC2 cache. Skipped (exit 77) when
// ../shared/data is absent. Arguments: <tests/data> <shared data> <tmp>.
"use strict";
const [, sharedDir, tmpDir] = core.scriptArguments();
core.include("test_asserts.js");
const {garment, clip, body: files} = sharedMakeHuman(sharedDir, "male_casualsuit04_pants_on_base.obj", "mesh");

core.makePath(tmpDir);
const frames = 60;
const crossings = {}, waistband = {};
for (const type of ["mesh", "capsules", "mesh+self", "mesh+self0"]) {
  const trousers = core.loadObject(garment, {units: "dm"});
  const info = core.objectInfo(trousers);
  const pc2 = tmpDir + "/trousers_07_06_" + type.replace("+", "_") + ".pc2";
  // With cloth-cloth contact: the default neighbourhood (26 mm), and none.
  const selfContact = type === "mesh+self" ? 0.003 : type === "mesh+self0" ? {thickness: 0.003, neighbourhood: 0} : 0;
  const report = multirescloth.recordInstance(trousers, {
    motion: {path: clip, units: "cmu"}, body: Object.assign({}, files, {type: type.split("+")[0]}), place: "makehuman",
    preroll: 0.5, frames: frames, output: pc2, selfContact: selfContact});
  crossings[type] = report.maxSelfCrossings;
  waistband[type] = report.maxPinnedStretch;
  print("character trousers (" + type + "): initialPenetration " + (1000 * report.preroll.initialPenetration).toFixed(2) +
        " mm, maxPenetration " + (1000 * report.maxPenetration).toFixed(2) + " mm, maxDepth " +
        (1000 * report.maxDepth).toFixed(2) + " mm at " + JSON.stringify(report.deepest) + ", maxStretch " +
        report.maxStretch.toFixed(3) + " (cloth " + report.maxClothStretch.toFixed(3) + ", waistband " +
        report.maxPinnedStretch.toFixed(3) + "), maxWaistError " + report.maxWaistError.toExponential(2) + " m, " +
        report.msPerFrame.total.toFixed(1) + " ms/frame, maxSelfCrossings " + report.maxSelfCrossings);
  expectEqual([report.frames, report.nonFinite, report.preroll.nonFinite, report.body, report.waistFollows],
              [frames, false, false, type.split("+")[0], "skin"], type + ": run completed, waist on the skin");
  if (!(report.maxWaistError <= 1e-9)) throw new Error(type + ": maxWaistError " + report.maxWaistError + " > 1e-9 m");
  expectEqual(core.fileSize(pc2), 32 + frames * info.vertices * 12, type + ": PC2 size");
  // Stated bounds (README, Known limits). On capsules the trousers start
  // within the thickness plus 2-3 mm where they were modelled that close
  // (4.3 mm measured); on the skinned mesh they are cleared of it first
  // (their waistband was modelled 2 mm inside). Depth inside the body
  // (issue 4: 2 mm): 0.0 mm on both (14 / 17.5 mm while the hands went
  // into the hips; 3.0 mm on the mesh before the waistband was cleared and
  // skin folded over behind the knees stopped counting as the outside).
  // Stretch: 8.9 / 8.9 % since the pins' weights are averaged over 2 cm
  // along the waist (the waistband's own 8.9 % on both); 28 % on both with
  // each pin's skin weights blended over its nearest surface point (all of
  // it the waistband's, below); 57 / 88 % before that, on the waistband's
  // edges next to pins that took neighbouring body vertices' unlike weights
  // (116 / 149 % before the contact planes). With cloth-cloth contact and no
  // neighbourhood (mesh+self0) 14.5 % (19 % with the fixed limiter estimate
  // 0.97); 72 % while a round could end on a contact push the limiter had
  // not seen.
  expectAtMost(report.preroll.initialPenetration, type === "mesh" ? 1e-9 : 0.007, type + ": initial penetration");
  expectAtMost(report.maxDepth, 0.002, type + ": depth inside the body");
  expectAtMost(report.maxStretch, 0.5, type + ": stretch");
}
// The waistband: its pins take the skin weights of the body under them,
// averaged over 2 cm along the waist by default (body.waistSmoothing).
// With each pin's own weights the band stretches with the skin over the
// hip, which linear blend skinning stretches as the thigh swings.
{
  const trousers = core.loadObject(garment, {units: "dm"});
  const own = multirescloth.simulate(trousers, {
    motion: {path: clip, units: "cmu"}, body: Object.assign({}, files, {type: "mesh", waistSmoothing: 0}),
    place: "makehuman", preroll: 0.5, frames: frames});
  print("character trousers (mesh, each pin its own skin's weights): maxStretch " + own.maxStretch.toFixed(3) +
        " (cloth " + own.maxClothStretch.toFixed(3) + ", waistband " + own.maxPinnedStretch.toFixed(3) + ")");
  expectEqual([own.waistSmoothing, own.maxWaistError <= 1e-9], [0, true], "waistSmoothing 0");
  expectAtLeast(own.maxPinnedStretch, 2 * waistband.mesh, "the waistband on its own skin's weights against smoothed");
}
// Cloth-cloth contact (README, Known limits): the legs' inner faces pass
// through each other without it (149 edge-triangle crossings at the worst
// frame), fewer with it: 88 with the default neighbourhood, which leaves
// out cloth joined within 26 mm along the sheet (some of these coarse
// edges are shorter), 14 with none. (With the limiter's fixed estimate
// 0.97 instead of the chain's: 307, 60 and 8.)
expectAtLeast(crossings.mesh, 100, "crossings without cloth-cloth contact");
expectAtMost(crossings["mesh+self"], 0.7 * crossings.mesh, "crossings with cloth-cloth contact");
expectAtMost(crossings["mesh+self0"], 40, "crossings with cloth-cloth contact and no neighbourhood");
print("character trousers: ok");
