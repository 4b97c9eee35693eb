// refineAdaptive on the 3 x 3 unit grid, with mode layouts whose results
// were worked out by hand from Algorithms 2-3 and 2:1 balance (vertex index
// = 4 * row + column, see tests/data/grid3x3.obj).
"use strict";
const [dataDir] = core.scriptArguments();

core.include("test_asserts.js");
function freshGrid() { return core.loadObject(dataDir + "/grid3x3.obj"); }
const allVertices = Array.from({length: 16}, (_, vertex) => vertex);
function counts(info) { return [info.vertices, info.faces, info.hangingNodes, info.facesPerLevel]; }
function reportCounts() {
  const report = multirescloth.lastReport();
  return [report.vertices, report.faces, report.hangingNodes, report.facesPerLevel,
          report.facesRefinedPerPass, report.facesRefinedForBalance];
}

// All modes 1 (the default): no face reaches delta 8.
let grid = freshGrid();
let refined = multirescloth.refineAdaptive(grid);
expectEqual(reportCounts(), [16, 9, 0, [0, 9], [], 0], "default modes: nothing to refine");

// All modes 2: every face sums to 8 once, then R drops to 1 -> uniform x1.
grid = freshGrid();
expectEqual(multirescloth.setModes(grid, allVertices, 2), 16, "setModes count");
expectThrows(() => multirescloth.setModes(grid, [0], 1e10), "ArgumentError", "mode must be an integer from 0 to 1000, got the number 1e+10");
expectThrows(() => multirescloth.setModes(grid, [0], 1001), "ArgumentError", "mode must be an integer from 0 to 1000");
refined = multirescloth.refineAdaptive(grid, {delta: 8, maxLevel: 3, balance: true});
expectEqual(reportCounts(), [49, 36, 0, [0, 0, 36], [9], 0], "all modes 2");

// Mode 3 on the centre face's corners (5, 6, 9, 10): pass 1 splits the centre
// face (sum 12) and its 4 edge neighbours (sum 8); pass 2 splits the centre's
// 4 children (sum 8 after Algorithm 3). 16 T-nodes: 2 per side of the level-3
// block, 2 per edge neighbour on the corner faces.
grid = freshGrid();
multirescloth.setModes(grid, [5, 6, 9, 10], 3);
refined = multirescloth.refineAdaptive(grid, {delta: 8, maxLevel: 3, balance: true});
expectEqual(reportCounts(), [53, 36, 16, [0, 4, 16, 16], [5, 4], 0], "mode 3 on the centre face");
const info = core.objectInfo(refined);
expectEqual(counts(info), [53, 36, 16, [0, 4, 16, 16]], "objectInfo agrees with the report");
expectEqual(info.maxLevel, 3, "maxLevel");
expectEqual(info.facesPerLevel.reduce((a, b) => a + b, 0), info.faces, "facesPerLevel sums to the faces");
expectEqual(info.verticesPerLevel.reduce((a, b) => a + b, 0), info.vertices, "verticesPerLevel sums to the vertices");
if (Math.abs(info.totalMass - 0.15 * info.area) > 1e-12 * info.totalMass) throw new Error("mass != 0.15 * area");
// The input is untouched (counts and modes).
expectEqual(counts(core.objectInfo(grid)), [16, 9, 0, [0, 9]], "input untouched");
expectEqual(multirescloth.getModes(grid), [1, 1, 1, 1, 1, 3, 3, 1, 1, 3, 3, 1, 1, 1, 1, 1], "input modes untouched");

// Same modes, maxLevel 2: only pass 1.
refined = multirescloth.refineAdaptive(grid, {maxLevel: 2});
expectEqual(reportCounts(), [37, 24, 8, [0, 4, 20], [5], 0], "maxLevel 2");
// maxLevel 1: nothing may be split.
refined = multirescloth.refineAdaptive(grid, {maxLevel: 1});
expectEqual(reportCounts(), [16, 9, 0, [0, 9], [], 0], "maxLevel 1");
// A higher delta: only the centre face (sum 12) reaches 10.
refined = multirescloth.refineAdaptive(grid, {delta: 10});
expectEqual(multirescloth.lastReport().facesRefinedPerPass[0], 1, "delta 10: first pass");

// A layout that needs 2:1 balance: mode 7 on vertex 5, 2 on vertex 0, 0
// elsewhere. Face (0,1,5,4) sums to 9 and splits, then its child at vertex 5
// (R 6 + 2.5 + 1.25 + 2.5) splits again, next to the unsplit faces (1,2,6,5)
// and (4,5,9,8): balance splits those two.
grid = freshGrid();
multirescloth.setModes(grid, allVertices, 0);
multirescloth.setModes(grid, [0], 2);
multirescloth.setModes(grid, [5], 7);
refined = multirescloth.refineAdaptive(grid, {balance: true});
expectEqual(reportCounts(), [34, 21, 8, [0, 6, 11, 4], [1, 1], 2], "balance on");
refined = multirescloth.refineAdaptive(grid, {balance: false});
expectEqual(reportCounts(), [26, 15, 6, [0, 8, 3, 4], [1, 1], 0], "balance off");

const report = multirescloth.lastReport();
expectEqual([report.operation, report.source, report.result, report.delta, report.maxLevel, report.balance,
             report.passes], ["refineAdaptive", grid, refined, 8, 3, false, 2], "report header");
print("adaptive grid: ok");
