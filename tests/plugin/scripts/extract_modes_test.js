// multirescloth.extractModes: a 12 x 12 sheet (the 3 x 3 grid refined
// twice) hangs from its top row and folds over a capsule; the modes learnt
// from that recording: the report's fields, exact counts against the mode
// layer, ordering, determinism, options, and each refused input.
// Arguments: <tests/data> <shared data> <tmp>.
"use strict";
const [dataDir, , tmpDir] = core.scriptArguments();

core.include("test_asserts.js");

core.makePath(tmpDir);
const grid = core.loadObject(dataDir + "/grid3x3.obj");
const sheet = multirescloth.refineUniform(grid, 2);
const vertices = core.objectInfo(sheet).vertices;
expectEqual(vertices, 169, "13 x 13 vertices");
const pc2 = tmpDir + "/fold.pc2";
const frames = 24;
const run = multirescloth.simulate(sheet, {
  frames: frames, substeps: 3, material: "silk", pins: "top", gravity: [0, -9.81, -4], output: pc2,
  colliders: [{type: "capsule", a: [-1, 1.5, -0.4], b: [4, 1.5, -0.4], radiusA: 0.25, radiusB: 0.25}],
});
expectEqual([run.frames, run.nonFinite], [frames, false], "the recording");

const report = multirescloth.extractModes(sheet, pc2, {clusters: 3, skipFrames: 4});
const types = {
  operation: "string", source: "number", cache: "string", frames: "number", firstFrame: "number", vertices: "number",
  clusters: "number", normalize: "string", seed: "number", restarts: "number", restartKept: "number",
  iterations: "number", inertia: "number", sizes: "array", centroids: "array", normalizedCentroids: "array",
  offset: "array", scale: "array", maxMeanCurvature: "number", milliseconds: "number",
};
for (const [key, type] of Object.entries(types)) expectType(report[key], type, "report." + key);
expectEqual([report.operation, report.source, report.cache], ["extractModes", sheet, pc2], "report header");
expectEqual([report.frames, report.firstFrame, report.vertices, report.clusters, report.normalize, report.seed],
            [frames - 4, 4, vertices, 3, "minmax", 1], "what was analysed");
expectEqual(multirescloth.lastReport(), report, "lastReport keeps it");

// The mode layer holds exactly the report's modes: counts per mode = sizes.
const modes = multirescloth.getModes(sheet);
const counts = [0, 0, 0];
for (const mode of modes) {
  if (!(mode >= 1 && mode <= 3)) throw new Error("mode " + mode + " outside 1..3");
  ++counts[mode - 1];
}
expectEqual(counts, report.sizes, "sizes count the layer's modes");
expectEqual(core.objectInfo(sheet).verticesPerMode, [0, ...report.sizes], "objectInfo agrees");
for (const size of report.sizes) if (!(size > 0)) throw new Error("an empty mode: " + report.sizes);
// Numbered by deformation: centroid mean curvature grows with the mode.
for (let m = 1; m < 3; ++m)
  if (!(report.centroids[m][0] > report.centroids[m - 1][0]))
    throw new Error("modes out of order: " + JSON.stringify(report.centroids));
// min-max normalisation: normalised = (feature - offset) / scale.
for (let m = 0; m < 3; ++m)
  for (let f = 0; f < 2; ++f)
    expectNear(report.normalizedCentroids[m][f], (report.centroids[m][f] - report.offset[f]) / report.scale[f], 1e-9,
               "normalised centroid " + m + "," + f);
if (!(report.maxMeanCurvature > 0)) throw new Error("the sheet folded, yet no curvature");

// The same call gives the same modes; options change what is recorded.
const again = multirescloth.extractModes(sheet, pc2, {clusters: 3, skipFrames: 4});
expectEqual(multirescloth.getModes(sheet), modes, "same seed, same modes");
expectEqual([again.sizes, again.inertia, again.centroids], [report.sizes, report.inertia, report.centroids], "same report");
const z = multirescloth.extractModes(sheet, pc2, {clusters: 2, normalize: "zscore", seed: 5, restarts: 3, maxFrames: 6});
expectEqual([z.clusters, z.normalize, z.seed, z.restarts, z.frames, z.firstFrame, z.sizes.length],
            [2, "zscore", 5, 3, 6, 0, 2], "zscore, two modes, six frames");
expectEqual(core.objectInfo(sheet).verticesPerMode, [0, ...z.sizes], "the layer follows the last extraction");

// Refused inputs name what is wrong; the layer is left alone.
const before = multirescloth.getModes(sheet);
const gridCache = tmpDir + "/grid.pc2";
multirescloth.simulate(grid, {frames: 2, pins: "top", output: gridCache});
expectThrows(() => multirescloth.extractModes(sheet, gridCache), "InputError", "grid.pc2", "16 points", "169");
expectThrows(() => multirescloth.extractModes(sheet, tmpDir + "/missing.pc2"), "InputError", "missing.pc2");
expectThrows(() => multirescloth.extractModes(sheet, pc2, {clusters: 0}), "ArgumentError", "option 'clusters'");
// More modes than a mode layer holds (kLargestMode): were they written, the
// .om and layer CSV files saved from the mesh would be refused on reading.
expectThrows(() => multirescloth.extractModes(sheet, pc2, {clusters: 1001}), "ArgumentError",
             "option 'clusters' must be an integer from 1 to 1000, got the number 1001");
expectThrows(() => multirescloth.extractModes(sheet, pc2, {restarts: 10001}), "ArgumentError",
             "option 'restarts' must be an integer from 1 to 10000, got the number 10001");
expectThrows(() => multirescloth.extractModes(sheet, pc2, {normalize: "log"}), "ArgumentError", "option 'normalize'");
expectThrows(() => multirescloth.extractModes(sheet, pc2, {skipFrames: frames}), "ArgumentError", "leaves none");
expectThrows(() => multirescloth.extractModes(sheet, pc2, {cluster: 3}), "ArgumentError", "unknown option 'cluster'");
expectThrows(() => multirescloth.extractModes(99, pc2), "ArgumentError", "no object with id 99");
expectEqual(multirescloth.getModes(sheet), before, "refused calls change no mode");
print("extractModes: ok");

// mapModes: the learnt modes onto the 3 x 3 grid the sheet was refined from.
multirescloth.extractModes(sheet, pc2, {clusters: 3});
const fine = multirescloth.getModes(sheet);
const mapped = multirescloth.mapModes(sheet, grid);
expectEqual([mapped.operation, mapped.source, mapped.result, mapped.method, mapped.vertices],
            ["mapModes", sheet, grid, "index", 16], "mapModes report");
expectEqual(multirescloth.getModes(grid), fine.slice(0, 16), "stable indices: coarse vertex i = refined vertex i");
const highest = multirescloth.mapModes(sheet, grid, {method: "highest"});
const coarseHighest = multirescloth.getModes(grid);
for (let v = 0; v < 16; ++v)
  if (!(coarseHighest[v] >= fine[v])) throw new Error("highest below the vertex's own mode at " + v);
expectEqual(highest.agreeHighest, coarseHighest.filter((m, v) => m === fine[v]).length, "agreeHighest counts");
expectEqual(multirescloth.mapModes(sheet, grid, {method: "frequent"}).method, "frequent", "frequent");
expectThrows(() => multirescloth.mapModes(grid, sheet), "ArgumentError", "fewer than the coarse mesh's");
expectThrows(() => multirescloth.mapModes(sheet, grid, {method: "mean"}), "ArgumentError", "option 'method'");
print("mapModes: ok");
