// A clip on another skeleton: CMU 16_15 in its DAZ-friendly conversion
// (43 joints named hip, abdomen, lThigh, ..., centimetres, ZXY channels)
// drives the shared skirt on the skinned MakeHuman body and on capsules
// fitted to it. `motion.joints` "auto" renames its joints onto the CMU
// names the rig, the waist and the capsules read; "asIs" leaves them, and
// the run is refused with the way out named. Units "auto" read it in
// centimetres; in CMU units it is refused. A CMU clip given Mixamo's
// names, or written Z up, runs as the clip itself. Skipped (exit 77) when
// ../shared/data is absent. Arguments: <tests/data> <shared data> <tmp>.
"use strict";
const [, sharedDir, tmpDir] = core.scriptArguments();
core.include("test_asserts.js");
const {garment, body: files} = sharedMakeHuman(sharedDir, "skirthelper.obj", "mesh");
const daz = sharedDir + "/motions/cmu_daz/16_15_daz.bvh";
skipUnlessFiles([daz]);

core.makePath(tmpDir);
const frames = 30;
const run = (type, joints, output) => {
  const skirt = core.loadObject(garment, {units: "dm"});
  const motion = {path: daz, units: "cm"};
  if (joints !== undefined) motion.joints = joints;
  try {
    return multirescloth.simulate(skirt, {motion: motion, body: Object.assign({}, files, {type: type}), place: "makehuman",
                                          preroll: 0.5, frames: frames, output: output});
  } finally {
    core.deleteObject(skirt);
  }
};

const reports = {};
for (const type of ["mesh", "capsules"]) {
  const report = run(type, undefined, tmpDir + "/daz_" + type + ".pc2");
  reports[type] = report;
  print("DAZ clip (" + type + "): maxDepth " + (1000 * report.maxDepth).toFixed(2) + " mm, maxPenetration " +
        (1000 * report.maxPenetration).toFixed(2) + " mm, maxStretch " + report.maxStretch.toFixed(3) +
        ", maxWaistError " + report.maxWaistError.toExponential(2) + " m, " + report.msPerFrame.total.toFixed(1) + " ms/frame");
  expectEqual([report.frames, report.nonFinite, report.preroll.nonFinite, report.body, report.waistFollows],
              [frames, false, false, type, "skin"], type + ": run completed, waist on the skin");
  if (!(report.maxWaistError <= 1e-9)) throw new Error(type + ": maxWaistError " + report.maxWaistError + " > 1e-9 m");
  // Issue 4's bounds for the CMU clips: no vertex 2 mm inside the body;
  // stretch as the skirt on CMU 07_06 (100 %). Measured: 0.0 mm on both,
  // 6 % on the mesh (31 % with the fixed limiter estimate 0.97), 4 % on
  // capsules (1226 % on the mesh while the DAZ hip branches were turned
  // onto their bones: the pelvis twisted).
  expectAtMost(report.maxDepth, 0.002, type + ": depth inside the body");
  expectAtMost(report.maxStretch, 1.0, type + ": stretch");
}
// What the report's fit asks of the skirt on this clip: its waist and
// hips fit (the top two levels: -3 and -6 % on the mesh), only its hem
// lacks girth at the stride (18 %). While the DAZ hands' finger joints
// (lIndex1, lMid1, ...) were not taken for the arm's, the hands hanging
// at the hips counted into the girth there: 73 and 32 %, and a warning
// that the waist lacked 73 %.
for (const type of ["mesh", "capsules"])
  for (const level of [0, 1])
    expectAtMost(reports[type].fit.levels[level].demand, 0, type + ": the fit's demand at level " + (level + 1));
// The hand's finger links get no capsules, as CMU's fingers do: 40
// capsules (60 with one on every finger bone).
expectAtMost(reports.capsules.capsules, 45, "capsules on the DAZ skeleton");

// The same renaming given by hand gives the same run, to the bit.
const byHand = {hip: "Hips", abdomen: "LowerBack", chest: "Spine1", neck: "Neck", head: "Head"};
for (const [s, side, hip] of [["l", "Left", "LHipJoint"], ["r", "Right", "RHipJoint"]]) {
  Object.assign(byHand, {[s + "Collar"]: side + "Shoulder", [s + "Shldr"]: side + "Arm", [s + "ForeArm"]: side + "ForeArm",
                         [s + "Hand"]: side + "Hand", [s + "Buttock"]: hip, [s + "Thigh"]: side + "UpLeg",
                         [s + "Shin"]: side + "Leg", [s + "Foot"]: side + "Foot"});
}
const sorted = (object) => Object.keys(object).sort().map((key) => key + ">" + object[key]).join(" ");
expectEqual(sorted(reports.mesh.jointsRenamed), sorted(byHand), "the report says which joints auto renamed");
const manual = run("mesh", byHand, tmpDir + "/daz_mesh_by_hand.pc2");
expectEqual([manual.maxStretch, manual.maxPenetration], [reports.mesh.maxStretch, reports.mesh.maxPenetration],
            "a hand-written renaming runs as auto");
expectEqual(core.filesEqual(tmpDir + "/daz_mesh_by_hand.pc2", tmpDir + "/daz_mesh.pc2"), true, "the same cache");

// Units: "auto" reads the centimetre clip in centimetres (the same run, to
// the bit); read in CMU units its figure is refused before the run, naming
// the units that fit, and nothing is written.
const runIn = (units, output) => {
  const skirt = core.loadObject(garment, {units: "dm"});
  try {
    return multirescloth.simulate(skirt, {motion: {path: daz, units: units}, body: Object.assign({}, files, {type: "mesh"}),
                                          place: "makehuman", preroll: 0.5, frames: frames, output: output});
  } finally {
    core.deleteObject(skirt);
  }
};
const automatic = runIn("auto", tmpDir + "/daz_mesh_auto.pc2");
expectEqual(automatic.motionUnits, "auto: cm", "auto units on the DAZ clip");
expectEqual(core.filesEqual(tmpDir + "/daz_mesh_auto.pc2", tmpDir + "/daz_mesh.pc2"), true, "auto runs as cm");
expectThrows(() => runIn("cmu", tmpDir + "/never.pc2"), "InputError", "option 'motion': ",
             "16_15_daz.bvh read in units 'cmu' (0.056444 m per unit): the figure's legs are 4.63 m long",
             "5.9 times an adult's 0.79 m; expected 0.4-2 times", "in 'cm' they are 0.82 m");
expectEqual(core.fileExists(tmpDir + "/never.pc2"), false, "nothing written for a figure in the wrong units");
const info = multirescloth.motionInfo({path: daz, units: "auto"});
expectEqual([info.units, info.metresPerUnit, info.frames, info.joints.length, info.jointsRenamed.lThigh],
            ["auto: cm", 0.01, 472, 43, "LeftUpLeg"], "motionInfo of the DAZ clip");
expectAtMost(Math.abs(info.legs - 0.8205), 0.001, "the DAZ figure's legs (m)");

// Left as they are, the names are refused, naming the option that renames them.
expectThrows(() => run("mesh", "asIs", tmpDir + "/never.pc2"), "InputError", "has no joint 'Hips'",
             "option 'motion.joints'", "{\"hip\": \"Hips\"}");
expectEqual(core.fileExists(tmpDir + "/never.pc2"), false, "nothing written for a refused run");
// Bad renamings name their entry.
expectThrows(() => run("mesh", {hips: "Hips"}, tmpDir + "/never.pc2"), "ArgumentError", "option 'motion'",
             "no joint \"hips\"");
expectThrows(() => run("mesh", {hip: "Hips", abdomen: "Hips"}, tmpDir + "/never.pc2"), "ArgumentError",
             "two joints would be named \"Hips\"");
expectThrows(() => run("mesh", 5, tmpDir + "/never.pc2"), "ArgumentError", "option 'motion.joints' must be",
             "\"auto\", \"asIs\"");
expectThrows(() => run("mesh", "cmu", tmpDir + "/never.pc2"), "ArgumentError", "option 'motion.joints'");

// Mixamo's names: CMU 07_06 with its joints named as Mixamo names them
// (the prefix, and its three spine joints one lower) runs, renamed back by
// "auto", to the same cache as the clip itself.
const walk = sharedDir + "/motions/cmu_mb/07_06.bvh";
skipUnlessFiles([walk]);
const mixamo = {Hips: "Hips", LowerBack: "Spine", Spine: "Spine1", Spine1: "Spine2"};
const text = core.readTextFile(walk).replace(/^(\s*(?:ROOT|JOINT)\s+)(\S+)/gm,
                                                 (line, head, name) => head + "mixamorig:" + (mixamo[name] || name));
core.writeTextFile(tmpDir + "/07_06_mixamo.bvh", text);
const walkRun = (path, output) => {
  const skirt = core.loadObject(garment, {units: "dm"});
  try {
    return multirescloth.simulate(skirt, {motion: {path: path, units: "cmu"}, body: Object.assign({}, files, {type: "mesh"}),
                                          place: "makehuman", preroll: 0.2, frames: 6, output: output});
  } finally {
    core.deleteObject(skirt);
  }
};
const asCmu = walkRun(walk, tmpDir + "/07_06.pc2");
// In inches the CMU figure has a toddler's legs, plausible alone but not as
// the MakeHuman body's skeleton: refused against the body.
expectThrows(() => multirescloth.simulate(core.loadObject(garment, {units: "dm"}), {
               motion: {path: walk, units: "inch"}, body: Object.assign({}, files, {type: "mesh"}), place: "makehuman",
               frames: 1, output: tmpDir + "/never.pc2"}),
             "InputError", "07_06.bvh read in units 'inch' (0.0254 m per unit): the figure's legs are 0.36 m long",
             "times the MakeHuman body's 0.8", "expected 0.67-1.5 times: check the units; in 'cmu' they are 0.81 m");
expectEqual(multirescloth.motionInfo({path: walk, units: "inch"}).units, "inch", "alone, a toddler passes");
expectEqual(core.fileExists(tmpDir + "/never.pc2"), false, "nothing written for a figure in the wrong units");
const asMixamo = walkRun(tmpDir + "/07_06_mixamo.bvh", tmpDir + "/07_06_mixamo.pc2");
expectEqual(Object.keys(asCmu.jointsRenamed).length, 0, "CMU names are kept");
expectEqual([Object.keys(asMixamo.jointsRenamed).length, asMixamo.jointsRenamed["mixamorig:Spine2"]], [31, "Spine1"],
            "every Mixamo name renamed");
expectEqual(core.filesEqual(tmpDir + "/07_06.pc2", tmpDir + "/07_06_mixamo.pc2"), true, "the same cache as the CMU clip");

// Other axes: 07_06 written Z up (every offset and position turned, each
// rotation channel relabelled to the turned axis, negated where it flips)
// is stood upright again by motion.axes "auto" and runs to the same cache;
// "asIs" leaves it lying, and the run differs.
const zUp = (bvh) => {
  // new x = x, new y = -z, new z = y: an upright figure then has its head along +z.
  const lines = bvh.split(/\r?\n/);
  const negate = [];
  let inMotion = false, framesFollow = false;
  const number = (x) => (Object.is(x, -0) ? "-0" : String(x));
  return lines.map((line) => {
    if (framesFollow && line.trim().length > 0)
      return line.trim().split(/\s+/).map((v, c) => number(negate[c] ? -Number(v) : Number(v))).join(" ");
    if (/^\s*MOTION/.test(line)) inMotion = true;
    if (inMotion && /^\s*Frame Time:/.test(line)) framesFollow = true;
    let m = line.match(/^(\s*OFFSET\s+)(\S+)\s+(\S+)\s+(\S+)\s*$/);
    if (m) return m[1] + [Number(m[2]), -Number(m[4]), Number(m[3])].map(number).join(" ");
    m = line.match(/^(\s*CHANNELS\s+\d+\s+)(.*)$/);
    if (m) {
      const names = m[2].trim().split(/\s+/).map((name) => {
        const axis = name[0], kind = name.slice(1);
        negate.push(axis === "Z");
        return (axis === "Y" ? "Z" : axis === "Z" ? "Y" : "X") + kind;
      });
      return m[1] + names.join(" ");
    }
    return line;
  }).join("\n");
};
core.writeTextFile(tmpDir + "/07_06_z_up.bvh", zUp(core.readTextFile(walk)));
const standing = walkRun(tmpDir + "/07_06_z_up.bvh", tmpDir + "/07_06_z_up.pc2");
expectEqual(standing.axesTurned, "x = x, y = z, z = -y", "the Z-up clip is turned upright");
expectEqual(asCmu.axesTurned, "", "an upright clip is not turned");
expectEqual(core.filesEqual(tmpDir + "/07_06.pc2", tmpDir + "/07_06_z_up.pc2"), true, "the same cache as the clip upright");
let lying = null;
try {
  const skirt = core.loadObject(garment, {units: "dm"});
  lying = multirescloth.simulate(skirt, {motion: {path: tmpDir + "/07_06_z_up.bvh", units: "cmu", axes: "asIs"},
                                         body: Object.assign({}, files, {type: "mesh"}), place: "makehuman", preroll: 0.2,
                                         frames: 6, output: tmpDir + "/07_06_lying.pc2"});
} catch (e) {
  print("lying: " + e.message);
}
expectEqual(lying !== null && core.filesEqual(tmpDir + "/07_06.pc2", tmpDir + "/07_06_lying.pc2"), false,
            "axes \"asIs\" leaves the clip lying: not the upright run");
expectThrows(() => multirescloth.simulate(core.loadObject(garment, {units: "dm"}),
                                         {motion: {path: walk, units: "cmu", axes: "z"}, frames: 1}),
             "ArgumentError", "option 'motion.axes'", "\"auto\"");
