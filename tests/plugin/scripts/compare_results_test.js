// multirescloth.compareResults: a result against itself is exactly 0 with all
// of its bending kept; coarser models of the same run are farther and keep
// less; a rigidly moved copy of the reference is exactly as far as it moved;
// and every mismatch is refused by name. Arguments: <tests/data> <shared data> <tmp>.
"use strict";
const [dataDir, , tmpDir] = core.scriptArguments();
core.include("test_asserts.js");
core.makePath(tmpDir);

// The 3 x 3 unit grid hanging from its top row (rows along y), sagging out of
// its plane, at three resolutions of the same coarse grid.
const coarse = core.loadObject(dataDir + "/grid3x3.obj");
const topRow = [12, 13, 14, 15];
const frames = 6;
function run(id, name) {
  const pc2 = tmpDir + "/" + name + ".pc2";
  multirescloth.simulate(id, {frames: frames, pins: topRow, gravity: [0, -9.81, -20], output: pc2});
  return pc2;
}
const high = multirescloth.refineUniform(coarse, 2);
const middle = multirescloth.refineUniform(coarse, 1);
multirescloth.setModes(high, [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15], 3);
const highCache = run(high, "high"), middleCache = run(middle, "middle"), coarseCache = run(coarse, "coarse");

// Itself: exactly 0, all of its bending kept.
const self = multirescloth.compareResults(high, highCache, high, highCache);
expectEqual([self.frames, self.points, self.meanRms, self.meanP95, self.maxDistance, self.wrinkleKept,
             self.wrinkleKeptRegion, self.wrinkleError, self.wrinkleErrorRegion, self.cancelled],
            [frames, core.objectInfo(high).vertices, 0, 0, 0, 1, 1, 0, 0, false], "a result against itself");
expectEqual(self.rmsPerFrame, new Array(frames).fill(0), "zero every frame");
expectEqual(self.regionMode, 3, "the highest mode by default");
expectEqual(multirescloth.lastReport().operation, "compareResults", "lastReport");

// Coarser models: farther from the reference, and keeping less of its bending.
const mid = multirescloth.compareResults(middle, middleCache, high, highCache);
const low = multirescloth.compareResults(coarse, coarseCache, high, highCache);
for (const [name, r] of [["middle", mid], ["coarse", low]]) {
  if (!(r.meanRms > 0 && r.meanP95 <= r.maxDistance && r.meanRms <= r.maxDistance))
    throw new Error(name + ": distances " + JSON.stringify([r.meanRms, r.meanP95, r.maxDistance]));
  expectEqual(r.rmsPerFrame.length, frames, name + " frames");
}
print("compareResults on the grid: middle RMS " + (1000 * mid.meanRms).toFixed(2) + " mm, kept " +
      (100 * mid.wrinkleKept).toFixed(1) + " %, error " + mid.wrinkleError.toFixed(3) + "; coarse RMS " +
      (1000 * low.meanRms).toFixed(2) + " mm, kept " + (100 * low.wrinkleKept).toFixed(1) + " %, error " +
      low.wrinkleError.toFixed(3));
// The grid sags smoothly: a coarser grid, bilinear in its faces, puts the
// same bending into kinks along its face edges, which the energy ratio counts
// (above 100 % here) and the error counts against it (above 1 here: worse
// than no bending at all), so on a smooth surface neither orders the models;
// the distance does.
if (!(mid.meanRms < low.meanRms)) throw new Error("the coarse grid should be farther than the middle one");
for (const [name, r] of [["middle", mid], ["coarse", low]])
  if (!(r.wrinkleKept > 1 && r.wrinkleError > 1)) throw new Error(name + ": kinks should count as bending");

// maxFrames; regionMode.
expectEqual(multirescloth.compareResults(middle, middleCache, high, highCache, {maxFrames: 2}).frames, 2, "maxFrames");
const absent = multirescloth.compareResults(middle, middleCache, high, highCache, {regionMode: 7});
expectEqual([absent.regionMode, absent.regionPoints, absent.wrinkleKeptRegion, absent.wrinkleErrorRegion], [7, 0, null, null],
            "an empty region has nothing measurable");

// Refusals, named.
expectThrows(() => multirescloth.compareResults(middle, highCache, high, highCache), "ArgumentError",
             "high.pc2", "points, the model has");
expectThrows(() => multirescloth.compareResults(middle, middleCache, high, tmpDir + "/missing.pc2"), "InputError",
             "referenceCachePath", "missing.pc2");
const short = tmpDir + "/short.pc2";
multirescloth.simulate(middle, {frames: 2, pins: topRow, output: short});
expectThrows(() => multirescloth.compareResults(middle, short, high, highCache), "ArgumentError", "frames",
             "expected the same, or maxFrames at most 2");
expectEqual(multirescloth.compareResults(middle, short, high, highCache, {maxFrames: 2}).frames, 2,
            "caches of other lengths over the frames both hold");
expectThrows(() => multirescloth.compareResults(middle, middleCache, high, highCache, {regionMode: 0}), "ArgumentError",
             "regionMode");
expectThrows(() => multirescloth.compareResults(middle, middleCache, high, highCache, {frames: 2}), "ArgumentError",
             "frames");
// The coarse grid re-exported with its faces in reverse order, or each
// started at its second corner, has the same count: refused, named.
const gridLines = core.readTextFile(dataDir + "/grid3x3.obj").split("\n");
const faceLines = gridLines.filter((line) => line.startsWith("f "));
const otherLines = gridLines.filter((line) => !line.startsWith("f "));
core.writeTextFile(tmpDir + "/reversed.obj", otherLines.concat(faceLines.slice().reverse()).join("\n") + "\n");
core.writeTextFile(tmpDir + "/rotated.obj", otherLines.concat(faceLines.map((line) => {
  const corners = line.trim().split(/\s+/).slice(1);
  return "f " + corners.slice(1).concat(corners.slice(0, 1)).join(" ");
})).join("\n") + "\n");
for (const name of ["reversed", "rotated"]) {
  const other = multirescloth.refineUniform(core.loadObject(tmpDir + "/" + name + ".obj"), 1);
  expectThrows(() => multirescloth.compareResults(other, middleCache, high, highCache), "ArgumentError",
               "coarse face 0 has corners", "must be refined from the same coarse mesh");
}
print("compareResults: ok (" + checked + " errors checked)");
