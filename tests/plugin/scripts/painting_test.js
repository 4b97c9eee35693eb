// Mode painting through the scripting API on the 3 x 3 unit grid (vertex
// index = 4 * row + column): the geodesic and threshold brushes, erasing
// back to the modes extractModes computed, layers, and CSV round trips.
// Arguments: <tests/data> <shared data> <tmp>.
"use strict";
const [dataDir, , tmpDir] = core.scriptArguments();

core.include("test_asserts.js");

core.makePath(tmpDir);
const grid = core.loadObject(dataDir + "/grid3x3.obj");
const selected = (mode) => {
  const ids = [];
  multirescloth.getModes(grid).forEach((m, v) => { if (m === mode) ids.push(v); });
  return ids;
};

// Geodesic: along the edges from vertex 5 at (1, 1): radius 1 reaches its 4
// neighbours, radius 2 also the 6 vertices two edges away (not across a diagonal).
expectEqual(multirescloth.paintModes(grid, {type: "geodesic", seeds: [5], radius: 1, mode: 3}), 5, "radius 1");
expectEqual(selected(3), [1, 4, 5, 6, 9], "geodesic radius 1");
expectEqual(multirescloth.paintModes(grid, {type: "geodesic", seeds: [5], radius: 2, mode: 4}), 11, "radius 2");
expectEqual(selected(4), [0, 1, 2, 4, 5, 6, 7, 8, 9, 10, 13], "geodesic radius 2");
// Threshold on any layer, here the mode layer itself.
expectEqual(multirescloth.paintModes(grid, {type: "threshold", layer: "mode", threshold: 4, mode: 2}), 11, "threshold");
expectEqual(multirescloth.paintModes(grid, {type: "threshold", layer: "mode", threshold: 1, below: true, mode: 5}), 5,
            "threshold below");
expectEqual(selected(5), [3, 11, 12, 14, 15], "the rest");
// Before any analysis, erasing goes back to the default mode.
expectEqual(multirescloth.eraseModes(grid, [3, 0]), 2, "erase two");
expectEqual(multirescloth.getModes(grid)[3], 1, "default mode");
expectEqual(multirescloth.eraseModes(grid), 14, "erase all the others");
expectEqual(multirescloth.getModes(grid), Array(16).fill(1), "all default");

// After extractModes: the computed layer, the features, erase back to them.
const pc2 = tmpDir + "/grid.pc2";
multirescloth.simulate(grid, {frames: 12, pins: [12, 13, 14, 15], gravity: [0, -9.81, -5], output: pc2});
const report = multirescloth.extractModes(grid, pc2, {clusters: 2});
const computed = multirescloth.getModes(grid);
expectEqual(multirescloth.getLayer(grid, "computed_mode"), computed, "computed layer = modes after extraction");
const mean = multirescloth.getLayer(grid, "mean_curvature");
expectEqual(mean.length, 16, "mean curvature per vertex");
const deviation = multirescloth.getLayer(grid, "curvature_deviation");
expectEqual(deviation.length, 16, "deviation per vertex");
// The threshold brush on the curvature: everything at or above the largest value.
const top = Math.max(...mean);
expectEqual(multirescloth.paintModes(grid, {type: "threshold", layer: "mean_curvature", threshold: top, mode: 7}),
            mean.filter((k) => k >= top).length, "curvature threshold");
multirescloth.setModes(grid, [0], 9);
const painted = multirescloth.getModes(grid);
expectEqual(multirescloth.eraseModes(grid), painted.filter((m, v) => m !== computed[v]).length, "erase counts changes");
expectEqual(multirescloth.getModes(grid), computed, "erased back to the computed modes");
expectEqual(report.sizes.reduce((a, b) => a + b, 0), 16, "sizes");

// Exports coloured by mode and by mean curvature (PLY vertex colours).
for (const colorBy of ["mode", "curvature"]) {
  const ply = tmpDir + "/grid_" + colorBy + ".ply";
  multirescloth.exportSurface(grid, ply, {colorBy: colorBy});
  if (!core.fileExists(ply)) throw new Error("no PLY coloured by " + colorBy);
}

// CSV: save, change, load back.
multirescloth.setModes(grid, [5, 6], 8);
const saved = multirescloth.getModes(grid);
const csv = tmpDir + "/grid_layers.csv";
multirescloth.saveLayers(grid, csv);
expectThrows(() => multirescloth.saveLayers(grid, tmpDir + "/grid_layers.pc2"), "ArgumentError",
             "multirescloth.saveLayers: path must end in .csv", "grid_layers.pc2");
if (!core.fileExists(csv)) throw new Error("no CSV at " + csv);
multirescloth.eraseModes(grid);
expectEqual(multirescloth.loadModes(grid, csv), 16, "rows read");
expectEqual(multirescloth.getModes(grid), saved, "modes back from the CSV");

// Refused brushes name what is wrong.
expectThrows(() => multirescloth.paintModes(grid, {type: "sphere", center: [0, 0, 0], radius: -1, mode: 2}), "ArgumentError",
             "option 'radius' must be a number >= 0 (metres), got -1");
expectThrows(() => multirescloth.paintModes(grid, {type: "geodesic", seeds: [16], radius: 1, mode: 2}), "ArgumentError",
             "seed vertex 16");
expectThrows(() => multirescloth.paintModes(grid, {type: "geodesic", center: [0, 0, 0], radius: 1, mode: 2}),
             "ArgumentError", "option 'center' belongs to the sphere brush");
expectThrows(() => multirescloth.paintModes(grid, {type: "threshold", layer: "wrinkles", threshold: 1, mode: 2}),
             "ArgumentError", "'wrinkles'", "mean_curvature");
expectThrows(() => multirescloth.paintModes(grid, {type: "lasso", mode: 2}), "ArgumentError", "option 'type'");
expectThrows(() => multirescloth.getLayer(grid, "nothing"), "ArgumentError", "no per-vertex layer 'nothing'");
const unanalysed = core.loadObject(dataDir + "/grid3x3.obj");
expectThrows(() => multirescloth.exportSurface(unanalysed, tmpDir + "/curvature.ply", {colorBy: "curvature"}), "ArgumentError",
             "no per-vertex layer 'mean_curvature'", "(the curvature layers come from analysing a cache of the mesh: extractModes)");
expectThrows(() => multirescloth.loadModes(grid, tmpDir + "/missing.csv"), "InputError", "missing.csv");
expectEqual(multirescloth.getModes(grid), saved, "refusals change nothing");
// core.writeTextFile: atomic, UTF-8; a missing folder is an OutputError.
core.writeTextFile(tmpDir + "/note.json", JSON.stringify({modes: report.sizes}) + "\n");
expectEqual(core.fileSize(tmpDir + "/note.json"), JSON.stringify({modes: report.sizes}).length + 1, "text file size");
expectThrows(() => core.writeTextFile(tmpDir + "/no/such/folder/x.txt", "x"), "OutputError", "x.txt");
print("painting: ok");
