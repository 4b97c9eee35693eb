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
for (const type of ["mesh", "capsules"]) {
  const trousers = core.loadObject(garment, {units: "dm"});
  const info = core.objectInfo(trousers);
  const pc2 = tmpDir + "/trousers_07_06_" + type + ".pc2";
  const report = multirescloth.recordInstance(trousers, {
    motion: {path: clip, units: "cmu"}, body: Object.assign({}, files, {type: type}), place: "makehuman",
    preroll: 0.5, frames: frames, output: pc2});
  print("character trousers (" + type + "): initialPenetration " + (1000 * report.preroll.initialPenetration).toFixed(2) +
        " mm, maxPenetration " + (1000 * report.maxPenetration).toFixed(2) + " mm, maxStretch " +
        report.maxStretch.toFixed(3) + ", maxWaistError " + report.maxWaistError.toExponential(2) + " m, " +
        report.msPerFrame.total.toFixed(1) + " ms/frame");
  expectEqual([report.frames, report.nonFinite, report.preroll.nonFinite, report.body, report.waistFollows],
              [frames, false, false, type, "skin"], type + ": run completed, waist on the skin");
  if (!(report.maxWaistError <= 1e-9)) throw new Error(type + ": maxWaistError " + report.maxWaistError + " > 1e-9 m");
  expectEqual(core.fileSize(pc2), 32 + frames * info.vertices * 12, type + ": PC2 size");
  // Stated bounds (README, Known limits), not issue 4's targets: the
  // trousers start within the thickness plus 2-3 mm where they were
  // modelled that close (6.0 / 4.3 mm measured); the pinned waistband
  // meets the swinging forearm (14 / 21.5 mm measured, issue 4's target is
  // 2 mm); the waistband's 5 mm edges and the crotch, where skinning
  // stretches the body's own skin by up to 180 %, stretch most (116 / 149 %).
  expectAtMost(report.preroll.initialPenetration, 0.007, type + ": initial penetration");
  expectAtMost(report.maxPenetration, 0.025, type + ": penetration");
  expectAtMost(report.maxStretch, 2.0, type + ": stretch");
}
print("character trousers: ok");
