// The shared MakeHuman skirt helper (decimetres, modelled on base.obj) worn
// by the skinned MakeHuman body walking the CMU instance clip 07_06 (CMU
// units): body "mesh", place "makehuman", 0.5 s of pre-roll, then 2 s of
// motion; then the same on capsules fitted to that body, and the
// knee-length skirt on them. Skipped (exit 77) when ../shared/data is absent.
// Arguments: <tests/data> <shared data> <tmp>.
"use strict";
const [, sharedDir, tmpDir] = core.scriptArguments();
core.include("test_asserts.js");
const {garment, clip, body} = sharedMakeHuman(sharedDir, "skirthelper.obj", "mesh");

core.makePath(tmpDir);
const skirt = core.loadObject(garment, {units: "dm"});
const info = core.objectInfo(skirt);
const frames = 60, pc2 = tmpDir + "/skirthelper_07_06.pc2";
const report = multirescloth.simulate(skirt, {
  motion: {path: clip, units: "cmu"}, body: body, place: "makehuman", preroll: 0.5, frames: frames, output: pc2});

const summary = "frames " + report.frames + ", preroll " + report.preroll.frames + " frames, maxStretch " +
                report.maxStretch.toFixed(4) + ", maxPenetration " + (1000 * report.maxPenetration).toFixed(3) +
                " mm, maxDepth " + (1000 * report.maxDepth).toFixed(3) + " mm, maxWaistError " +
                report.maxWaistError.toExponential(2) + " m, initialPenetration (rest) " +
                (1000 * report.preroll.initialPenetration).toFixed(3) + " mm, preroll maxPenetration " +
                (1000 * report.preroll.maxPenetration).toFixed(3) + " mm, " + report.msPerFrame.total.toFixed(1) +
                " ms/frame (dynamics " + report.msPerFrame.dynamics.toFixed(1) + ", collision " +
                report.msPerFrame.collision.toFixed(1) + "), body " + report.bodyVertices + " vertices";
print("character mesh: " + summary);
expectEqual([report.frames, report.nonFinite, report.cancelled, report.preroll.nonFinite], [frames, false, false, false],
            "run completed");
expectEqual([report.body, report.motionUnits, report.place, report.preroll.frames, report.legBridges],
            ["mesh", "cmu", "makehuman", 15, 2], "character fields (bridges to the ankles: the skirt reaches below the knees)");
expectEqual(report.handMittens, 2, "the hands collide as one capsule each (handMittens, the default)");
if (!(report.pinnedVertices > 0)) throw new Error("no waist pinned");
if (!(report.maxWaistError <= 1e-9)) throw new Error("maxWaistError " + report.maxWaistError + " > 1e-9 m");
// The pre-roll starts from the body's A-pose, which base.obj and the skirt
// were modelled in: the skirt starts within the body's 4 mm thickness (it
// started 53 mm inside the T-posed legs before).
expectAtMost(report.preroll.initialPenetration, 0.004, "initial penetration in the A-pose");
// On the mesh body the waist follows the skin under it (the MakeHuman waist
// bends with the lower back): pinned rigidly to the pelvis it ended 10 mm
// inside the body. Issue 4's target: no vertex more than 2 mm inside the
// body at any output frame (measured 0.0 mm; 1.2 mm before the arms were
// kept out of the hips, where the hands pinched the waistband).
expectEqual(report.waistFollows, "skin", "the waist follows the skin on the mesh body");
expectAtMost(report.maxDepth, 0.002, "depth inside the body during the motion (issue 4: 2 mm)");
expectAtMost(report.maxPenetration, 0.006, "penetration of body + 4 mm thickness during the motion");
if (!(report.armsOpened.maxDegrees > 0)) throw new Error("07_06's hands should have been kept out of the hips");
// The stated bound: the ankle-length tube spans the stride between the
// legs, and a few hem edges stretch most (72 % measured; 38 % with the
// fixed limiter estimate 0.97, 83 % before the pins' skin weights were
// blended; 40-133 % on the other shared walks then;
// the hem's path between the legs is chaotic). Before
// points a shin had swept more than half through went out where they
// entered, it was 291 %: the cloth ended on both sides of the shin.
expectAtMost(report.maxStretch, 1.0, "stretch");
expectAtMost(report.maxTearOpening, 0.0, "tear opening (an edge at least doubled)");
// Only vertices collide: the coarse skirt's 2-4 cm faces resting on the hips
// sink into the body between their corners (34 mm measured at 5ef9014),
// which the report says beside the vertices' depth.
if (!(report.maxFaceDepth > 0.01 && report.maxFaceDepth > report.maxDepth))
  throw new Error("maxFaceDepth " + report.maxFaceDepth + ": expected the coarse faces to sink more than 1 cm in");
expectEqual(core.fileSize(pc2), 32 + frames * info.vertices * 12, "PC2 size");

// The same skirt on capsules fitted to the body (bridges to the ankles too).
const onCapsules = multirescloth.simulate(core.loadObject(garment, {units: "dm"}), {
  motion: {path: clip, units: "cmu"}, body: Object.assign({}, body, {type: "capsules"}), place: "makehuman",
  preroll: 0.5, frames: frames});
print("character mesh: the shared skirt on fitted capsules: maxStretch " + onCapsules.maxStretch.toFixed(3) +
      ", maxPenetration " + (1000 * onCapsules.maxPenetration).toFixed(2) + " mm, maxDepth " +
      (1000 * onCapsules.maxDepth).toFixed(2) + " mm");
expectEqual([onCapsules.frames, onCapsules.nonFinite, onCapsules.body, onCapsules.legBridges], [frames, false, "capsules", 2],
            "the shared skirt on capsules");
if (!(onCapsules.maxWaistError <= 1e-9)) throw new Error("capsules: maxWaistError " + onCapsules.maxWaistError);
// Measured 0.0 mm inside, 1.3 mm into the thickness, and 30 % (168 % before the pins' skin
// weights were blended, 313 % before the contact planes).
expectAtMost(onCapsules.maxDepth, 0.002, "the shared skirt on capsules: depth (issue 4: 2 mm)");
expectAtMost(onCapsules.maxPenetration, 0.006, "the shared skirt on capsules: penetration");
expectAtMost(onCapsules.maxStretch, 1.0, "the shared skirt on capsules: stretch");
print("character mesh: the shared skirt on fitted capsules: maxTearOpening " + (1000 * onCapsules.maxTearOpening).toFixed(1) + " mm");

// Capsules fitted to the same body, under the knee-length skirt: the fit
// centres them in the limbs (twins across the pelvis and chest) and shrinks
// those the skirt starts inside of, and the waist follows the skin.
const kneeSkirt = sharedDir + "/garments/makehuman/female_elegantsuit01_skirt_on_base.obj";
if (core.fileExists(kneeSkirt)) {
  const knee = core.loadObject(kneeSkirt, {units: "dm"});
  const caps = multirescloth.simulate(knee, {
    motion: {path: clip, units: "cmu"}, body: Object.assign({}, body, {type: "capsules"}), place: "makehuman",
    preroll: 0.5, frames: frames});
  print("character mesh: capsules fitted to the body, knee-length skirt: " + caps.capsules + " capsules, " +
        caps.capsulesShrunk + " shrunk, initialPenetration " + (1000 * caps.preroll.initialPenetration).toFixed(2) +
        " mm, maxPenetration " + (1000 * caps.maxPenetration).toFixed(2) + " mm, maxDepth " +
        (1000 * caps.maxDepth).toFixed(2) + " mm, maxStretch " + caps.maxStretch.toFixed(3));
  expectEqual([caps.body, caps.waistFollows, caps.nonFinite], ["capsules", "skin", false], "capsule fields");
  if (!(caps.capsulesShrunk > 0)) throw new Error("the fitted capsules should have been shrunk to clear the skirt");
  // Before the centring fit and the shrink it started 62 mm inside them.
  expectAtMost(caps.preroll.initialPenetration, 0.004, "capsules: initial penetration");
  if (!(caps.maxWaistError <= 1e-9)) throw new Error("capsules: maxWaistError " + caps.maxWaistError);
  // Measured over 2 s: 0.0 mm inside, 1.3 mm into the thickness, 4 %
  // stretch (12 % before the pins' skin weights were blended; 9.6 mm and
  // 77 % while the swinging forearm went through the pinned waistband; 645
  // % before the fitted, centred capsules).
  expectAtMost(caps.maxDepth, 0.002, "capsules: depth (issue 4: 2 mm)");
  expectAtMost(caps.maxPenetration, 0.004, "capsules: penetration");
  expectAtMost(caps.maxStretch, 0.1, "capsules: stretch");

  // Refined once, its new points lie on chords of the curved body: they are
  // moved out before the run, so nothing starts inside (a coarse garment is
  // left as modelled). 6.4 mm inside at two levels before this.
  const refined = multirescloth.refineUniform(knee, 1);
  const onMesh = multirescloth.simulate(refined, {
    motion: {path: clip, units: "cmu"}, body: Object.assign({}, body, {type: "mesh"}), place: "makehuman",
    preroll: 0.1, frames: 1});
  print("character mesh: knee-length skirt refined once: " + onMesh.garmentCleared.vertices + " vertices cleared, " +
        "at most " + (1000 * onMesh.garmentCleared.largestMove).toFixed(2) + " mm");
  if (!(onMesh.garmentCleared.vertices > 0)) throw new Error("the refined skirt should have been cleared of the body");
  expectAtMost(onMesh.preroll.initialPenetration, 1e-9, "refined on the mesh: initial penetration");
  const coarseOnMesh = multirescloth.simulate(knee, {
    motion: {path: clip, units: "cmu"}, body: Object.assign({}, body, {type: "mesh"}), place: "makehuman",
    preroll: 0.1, frames: 1});
  // Garments as modelled are cleared too: MakeHuman's sit within 5 mm of
  // the body, some of it inside, and a pinned waist stays where it starts.
  if (!(coarseOnMesh.garmentCleared.vertices > 0 && coarseOnMesh.garmentCleared.largestMove < 0.01))
    throw new Error("the coarse skirt should have been cleared of the body by less than 1 cm: " +
                    JSON.stringify(coarseOnMesh.garmentCleared));
  expectAtMost(coarseOnMesh.preroll.initialPenetration, 1e-9, "coarse on the mesh: initial penetration");
}
print("character mesh: ok");
