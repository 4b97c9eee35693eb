// extractModes says what a cache would make its modes of (run_and_check
// checks the warnings): a cache of the grid at a tenth of its size (another
// mesh, or other units: its pairs at 0.1 times their rest distance), and a
// still cache (no bending: the modes would split rounding); a still cache
// with more clusters than its curvature has values is refused, naming it.
// Arguments: <tests/data> <shared data> <tmp>.
"use strict";
const [dataDir, , tmpDir] = core.scriptArguments();
core.include("test_asserts.js");
core.makePath(tmpDir);
const grid = core.loadObject(dataDir + "/grid3x3.obj");
const small = core.loadObject(dataDir + "/grid3x3.obj", {units: "dm"});
const sag = {frames: 4, pins: [12, 13, 14, 15], gravity: [0, -9.81, -20]};
const smallCache = tmpDir + "/small.pc2";
multirescloth.simulate(small, Object.assign({output: smallCache}, sag));
expectEqual(multirescloth.extractModes(grid, smallCache, {clusters: 2}).frames, 4, "read, with a warning");
// Still: every vertex pinned, nothing moves.
const stillCache = tmpDir + "/still.pc2";
multirescloth.simulate(grid, {frames: 3, pins: Array.from({length: 16}, (_, k) => k), output: stillCache});
expectEqual(multirescloth.extractModes(grid, stillCache, {clusters: 1}).sizes, [16], "one mode, with a warning");
expectThrows(() => multirescloth.extractModes(grid, stillCache, {clusters: 3}), "ArgumentError", "still.pc2",
             "fewer distinct values", "than the 3 clusters asked for");
// The grid's own sagging cache: neither.
const ownCache = tmpDir + "/own.pc2";
multirescloth.simulate(grid, Object.assign({output: ownCache}, sag));
multirescloth.extractModes(grid, ownCache, {clusters: 2});
print("extract warnings: ok");
