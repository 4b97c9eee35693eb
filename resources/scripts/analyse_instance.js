// The paper's section 4 on real data: a MakeHuman garment refined uniformly
// twice, recorded on a CMU walk with the skinned MakeHuman body (the
// instance), analysed into deformation modes, the modes mapped onto the
// coarse garment; writes the cache, the coloured meshes, the layers and the
// report. Uses only the public scripting API.
//
//   mrcloth -b resources/scripts/analyse_instance.js -- <shared data> <out dir>
//       [frames=200] [garment=skirthelper.obj] [levels=2] [body=mesh|capsules] [preroll=0.5] [fps=60]
//       [motion=<shared data>/motions/cmu_mb/07_06.bvh] [motion units=cmu]
//
// The garment is a file name in <shared data>/garments/makehuman/ (the
// skirts, or male_casualsuit04_pants_on_base.obj) or a path; any BVH with
// CMU joint names can be the motion.
//
// Everything is in metres; the garment files are decimetres, the clip CMU
// units. 07_06 lasts 3.47 s: 200 frames at 60 fps (3.33 s) stay within it,
// at 30 fps the last 95 would hold its final pose.
"use strict";
const args = core.scriptArguments();
if (args.length < 2) throw new Error("usage: analyse_instance.js -- <shared data> <out dir> [frames] [garment] [levels] [body] [preroll]");
const [sharedDir, outDir] = args;
const frames = args.length > 2 ? Number(args[2]) : 200;
const garmentName = args.length > 3 ? args[3] : "skirthelper.obj";
const levels = args.length > 4 ? Number(args[4]) : 2;
const bodyType = args.length > 5 ? args[5] : "mesh";
const preroll = args.length > 6 ? Number(args[6]) : 0.5;
const fps = args.length > 7 ? Number(args[7]) : 60;
const clip = args.length > 8 ? args[8] : sharedDir + "/motions/cmu_mb/07_06.bvh";
const clipUnits = args.length > 9 ? args[9] : "cmu";

const makehuman = sharedDir + "/bodies/makehuman";
const garmentPath = garmentName.includes("/") ? garmentName : sharedDir + "/garments/makehuman/" + garmentName;
for (const path of [garmentPath, clip, makehuman + "/base.obj"])
  if (!core.fileExists(path)) throw new Error("missing input " + path + " (the shared data must sit beside the checkout)");
core.makePath(outDir);
const stem = outDir + "/" + garmentName.split("/").pop().replace(/\.obj$/, "");

const coarse = core.loadObject(garmentPath, {units: "dm"});
const high = multirescloth.refineUniform(coarse, levels);
const info = core.objectInfo(high);
print("instance: " + garmentName + " refined " + levels + "x: " + info.vertices + " vertices; " + frames +
      " frames at " + fps + " fps of " + clip.split("/").pop() + " on the " + bodyType + " body after " + preroll + " s of pre-roll");

const body = {type: bodyType, obj: makehuman + "/base.obj", skeleton: makehuman + "/rigs/cmu_mb.mhskel",
              weights: makehuman + "/rigs/default_weights.mhw"};
const record = multirescloth.recordInstance(high, {
  motion: {path: clip, units: clipUnits}, body: body, place: "makehuman", preroll: preroll, frames: frames, fps: fps,
  output: stem + "_instance.pc2"});
print("recorded: " + record.frames + " frames, " + record.msPerFrame.total.toFixed(1) + " ms/frame (dynamics " +
      record.msPerFrame.dynamics.toFixed(1) + ", collision " + record.msPerFrame.collision.toFixed(1) +
      "), max stretch " + (100 * record.maxStretch).toFixed(1) + " %, max penetration " +
      (1000 * record.maxPenetration).toFixed(1) + " mm");

const modes = multirescloth.extractModes(high, record.output, {clusters: 3, normalize: "minmax", seed: 1});
print("modes: sizes " + JSON.stringify(modes.sizes) + ", centroids (1/m) " +
      JSON.stringify(modes.centroids.map((c) => c.map((x) => Number(x.toFixed(3))))) + ", " +
      modes.milliseconds.toFixed(0) + " ms");
const mapped = multirescloth.mapModes(high, coarse, {method: "index"});
print("mapped onto the coarse garment: " + mapped.changed + " of " + mapped.vertices + " vertices changed; " +
      "the index rule agrees with the cell's highest mode at " + mapped.agreeHighest + ", its most frequent at " +
      mapped.agreeFrequent);

multirescloth.exportSurface(high, stem + "_high_modes.ply", {colorBy: "mode"});
multirescloth.exportSurface(high, stem + "_high_curvature.ply", {colorBy: "curvature"});
multirescloth.exportSurface(coarse, stem + "_coarse_modes.ply", {colorBy: "mode"});
core.saveObject(high, stem + "_high.om");
core.saveObject(coarse, stem + "_coarse.om");
multirescloth.saveLayers(high, stem + "_high_layers.csv");
multirescloth.saveLayers(coarse, stem + "_coarse_layers.csv");
const report = {garment: garmentName, motion: clip, levels: levels, body: bodyType, fps: fps, record: record, modes: modes,
                mapping: mapped};
core.writeTextFile(stem + "_analysis.json", JSON.stringify(report, null, 1) + "\n");
print("wrote " + stem + "_{instance.pc2, high_modes.ply, high_curvature.ply, coarse_modes.ply, high.om, coarse.om, " +
      "high_layers.csv, coarse_layers.csv, analysis.json}");
