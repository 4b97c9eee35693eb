// Instance analysis end to end on real data: the shared skirt refined twice
// (11088 vertices), a short instance on CMU 07_06 with capsules fitted to
// the MakeHuman body, three modes, mapped onto the coarse skirt. Every mode
// must be non-empty and the outputs complete. Skipped (exit 77) when
// ../shared/data is absent. Arguments: <tests/data> <shared data> <tmp>.
"use strict";
const [, sharedDir, tmpDir] = core.scriptArguments();
core.include("test_asserts.js");
const {garment, clip, body} = sharedMakeHuman(sharedDir, "skirthelper.obj", "capsules");

core.makePath(tmpDir);
const coarse = core.loadObject(garment, {units: "dm"});
const high = multirescloth.refineUniform(coarse, 2);
expectEqual(core.objectInfo(high).vertices, 11088, "the shared skirt refined twice");
const frames = 8, pc2 = tmpDir + "/instance_short.pc2";
const record = multirescloth.recordInstance(high, {
  motion: {path: clip, units: "cmu"}, place: "makehuman", preroll: 0.2, frames: frames, fps: 60, output: pc2,
  body: body});
expectEqual([record.frames, record.nonFinite], [frames, false], "the recording");
expectEqual(core.fileSize(pc2), 32 + frames * 11088 * 12, "PC2 size");

const modes = multirescloth.extractModes(high, pc2, {clusters: 3});
print("analysis on real data: sizes " + JSON.stringify(modes.sizes) + ", centroids " + JSON.stringify(modes.centroids) +
      ", " + modes.milliseconds.toFixed(0) + " ms");
expectEqual([modes.frames, modes.vertices, modes.sizes.length], [frames, 11088, 3], "what was analysed");
for (const size of modes.sizes) if (!(size > 0)) throw new Error("an empty mode: " + JSON.stringify(modes.sizes));
expectEqual(modes.sizes.reduce((a, b) => a + b, 0), 11088, "every vertex has a mode");
for (let m = 1; m < 3; ++m)
  if (!(modes.centroids[m][0] > modes.centroids[m - 1][0])) throw new Error("modes out of order: " + JSON.stringify(modes.centroids));
// A skirt around a body bends everywhere (a tube of radius ~0.15 m is ~7 /m):
// the least deformed mode's centroid is positive and finite.
if (!(modes.centroids[0][0] > 0 && modes.centroids[2][0] < 1e4)) throw new Error("implausible curvature " + modes.centroids);

const mapped = multirescloth.mapModes(high, coarse, {method: "highest"});
expectEqual(mapped.vertices, 720, "coarse vertices");
const coarseModes = multirescloth.getModes(coarse);
const fine = multirescloth.getModes(high);
for (let v = 0; v < 720; ++v)
  if (!(coarseModes[v] >= fine[v])) throw new Error("the highest in a cell is below the vertex's own mode at " + v);
multirescloth.saveLayers(high, tmpDir + "/high_layers.csv");
multirescloth.exportSurface(high, tmpDir + "/high_curvature.ply", {colorBy: "curvature"});
multirescloth.exportSurface(coarse, tmpDir + "/coarse_modes.ply", {colorBy: "mode"});
for (const file of ["/high_layers.csv", "/high_curvature.ply", "/coarse_modes.ply"])
  if (!core.fileExists(tmpDir + file)) throw new Error("missing " + file);
print("analysis on real data: ok");
