// mrcloth quick tour (about 15 s): from a coarse garment to the meshes the
// paper compares, with hand-painted modes. The main job, with modes learnt
// from a recorded instance, is `mrcloth pipeline` (pipeline.js).
//
//   coarse garment --refineUniform x2--> high-resolution (instance) mesh
//   coarse garment --paint modes--> --refineAdaptive--> multi-resolution mesh
//
// The modes are painted by hand (a brush over the front of the lower skirt,
// where a walk wrinkles it most), as an artist would override them. Modes live on the coarse mesh because adaptive refinement
// starts from it (paper, Stage 6); maxLevel 3 = the instance mesh's level, so
// the multi-resolution mesh never gets finer than the high-resolution one.
//
// With the default garment it then records the high-resolution skirt on the
// instance walk and simulates the coarse skirt and the trousers on the new
// walk, on the embedded mannequin (PC2 caches with their rest OBJs).
//
// Usage: mrcloth -b quick_tour.js [-- <output folder> [<garment file> [<units>]]]
//   output folder  created if missing (default "out")
//   garment file   default: the embedded default skirt (resources/garments)
//   units          of the garment file: m (default), dm, cm, mm, inch
"use strict";

const args = core.scriptArguments();
const outDir = args[0] || "out";
const garmentPath = args[1] || core.resourcePath() + "/garments/default_skirt.obj";
const units = args[2] || "m";

const adaptiveOptions = {delta: 8, maxLevel: 3, balance: true};

if (!core.fileExists(garmentPath))
  throw new Error("garment not found: " + garmentPath +
                  " (pass another one: mrcloth -b quick_tour.js -- <out> <garment.obj> [units])");
core.makePath(outDir);

// --- Stage 0: the coarse garment -------------------------------------------
let started = Date.now();
const coarse = core.loadObject(garmentPath, {units: units});
const loadMilliseconds = Date.now() - started;

// --- Stage 1: the high-resolution mesh (two uniform refinements) -----------
const high = multirescloth.refineUniform(coarse, 2);
const highReport = multirescloth.lastReport();

// --- Stage 5: paint modes on the coarse mesh --------------------------------
// Brush centre: middle of the garment in x, a quarter of its height above the
// hem, on its front surface (+z, the mannequin faces +z). Mode 2 first with a
// wide brush, then mode 3 over the middle of it, so mode 2 rings mode 3.
const box = core.objectInfo(coarse).bbox;
const height = box.max[1] - box.min[1];
const brushCenter = [(box.min[0] + box.max[0]) / 2, box.min[1] + 0.25 * height, box.max[2]];
multirescloth.paintModes(coarse, {center: brushCenter, radius: 0.7 * height, mode: 2});
multirescloth.paintModes(coarse, {center: brushCenter, radius: 0.35 * height, mode: 3});
const coarseInfo = core.objectInfo(coarse);

// --- Stage 6: adaptive refinement -------------------------------------------
const multi = multirescloth.refineAdaptive(coarse, adaptiveOptions);
const multiReport = multirescloth.lastReport();

// --- Results -----------------------------------------------------------------
started = Date.now();
const written = [];
function save(id, fileName) {
  core.saveObject(id, outDir + "/" + fileName);
  written.push(fileName);
}
function exportColored(id, fileName, colorBy) {
  multirescloth.exportSurface(id, outDir + "/" + fileName, {colorBy: colorBy});
  written.push(fileName);
}
save(coarse, "coarse.om");
exportColored(coarse, "coarse_by_mode.ply", "mode");
save(high, "high_uniform.om");
exportColored(high, "high_uniform_by_level.ply", "level");
save(multi, "multires.om");
exportColored(multi, "multires_by_level.ply", "level");
exportColored(multi, "multires_by_mode.ply", "mode");
const saveMilliseconds = Date.now() - started;

// --- Stage 2: the instance and a new motion on the embedded mannequin -------
// The garments are modelled on the mannequin's T-pose (frame 0 of its
// clips): place "firstFrame". Capsules along the bones collide; a skirt gets
// bridges between the legs automatically. Two seconds of each motion after a
// one-second pre-roll; the paper's instance is 200 frames (recordInstance's
// default), shortened here so the main job stays quick.
const characters = core.resourcePath() + "/characters";
const motionFrames = 60;
const runs = [];
function onCharacter(label, id, motionFile, record) {
  const options = {motion: characters + "/" + motionFile, body: "capsules", place: "firstFrame",
                   frames: motionFrames, output: outDir + "/" + label + ".pc2"};
  const report = record ? multirescloth.recordInstance(id, options) : multirescloth.simulate(id, options);
  written.push(label + ".pc2", label + ".obj");
  runs.push({label: label, motion: motionFile, report: report});
}
const usesDefaultGarment = args[1] === undefined;
if (usesDefaultGarment) {
  onCharacter("instance_high_walk", high, "walk_instance.bvh", true);
  onCharacter("coarse_walk_new", coarse, "walk_new.bvh", false);
  const trousers = core.loadObject(core.resourcePath() + "/garments/default_trousers.obj");
  onCharacter("trousers_walk_new", trousers, "walk_new.bvh", true);
}

// --- Summary -------------------------------------------------------------------
const highInfo = core.objectInfo(high);
const multiInfo = core.objectInfo(multi);

function cell(value, width) { return String(value).padStart(width); }
function levels(info) {
  const counts = [];
  for (let level = 1; level < info.facesPerLevel.length; ++level) counts.push(info.facesPerLevel[level]);
  return counts.join("/");
}
function row(label, info, milliseconds) {
  return label.padEnd(22) + cell(info.vertices, 9) + cell(info.faces, 8) + cell(info.hangingNodes, 9) +
         "  " + levels(info).padEnd(16) + cell(info.totalMass.toPrecision(4), 9) +
         cell(milliseconds === undefined ? "-" : milliseconds.toFixed(1), 9);
}

const modeCounts = coarseInfo.verticesPerMode;
print("mrcloth quick tour");
print("garment: " + garmentPath + " (" + units + "), " + coarseInfo.vertices + " vertices, " +
      coarseInfo.faces + " quads, area " + coarseInfo.area.toFixed(4) + " m^2, loaded in " +
      loadMilliseconds + " ms");
print("modes painted on the coarse mesh: " +
      modeCounts.map((count, mode) => mode > 0 && count > 0 ? "mode " + mode + ": " + count : null)
          .filter(text => text !== null).join(", ") + " vertices (brush centre [" +
      brushCenter.map(x => x.toFixed(3)).join(", ") + "] m)");
print("adaptive refinement: delta " + adaptiveOptions.delta + ", maxLevel " + adaptiveOptions.maxLevel +
      ", balance " + adaptiveOptions.balance + "; faces refined per pass [" +
      multiReport.facesRefinedPerPass.join(", ") + "], " + multiReport.facesRefinedForBalance +
      " more for 2:1 balance");
print("");
print("mesh".padEnd(22) + cell("vertices", 9) + cell("faces", 8) + cell("hanging", 9) + "  " +
      "faces L1/L2/L3".padEnd(16) + cell("mass kg", 9) + cell("ms", 9));
print(row("coarse (modes)", coarseInfo));
print(row("high-res uniform x2", highInfo, highReport.milliseconds));
print(row("multi-resolution", multiInfo, multiReport.milliseconds));
print("");
print("multi-resolution / high-res vertices: " + (100 * multiInfo.vertices / highInfo.vertices).toFixed(1) + " %");
print("mass = " + coarseInfo.arealDensity + " kg/m^2 x area, the same on every mesh");
if (runs.length > 0) {
  print("");
  print("on the mannequin (capsules, " + motionFrames + " frames at 30 fps, 120 Hz steps):");
  print("run".padEnd(22) + "motion".padEnd(19) + cell("vertices", 9) + cell("ms/frame", 10) + cell("stretch %", 11) +
        cell("penetr. mm", 12) + cell("waist m", 10));
  for (const r of runs) {
    const t = r.report;
    if (t.nonFinite) throw new Error(r.label + ": the simulation produced a non-finite value");
    print(r.label.padEnd(22) + r.motion.padEnd(19) + cell(t.vertices, 9) + cell(t.msPerFrame.total.toFixed(1), 10) +
          cell((100 * t.maxStretch).toFixed(1), 11) + cell((1000 * t.maxPenetration).toFixed(2), 12) +
          cell(t.maxWaistError.toExponential(1), 10));
  }
}
print("wrote " + written.length + " files to " + outDir + " in " + saveMilliseconds + " ms: " + written.join(", "));
