// multirescloth.simulate on the 3 x 3 unit grid (vertex index = 4 * row +
// column, rows along y, see tests/data/grid3x3.obj): the report's fields and
// types, exact counts, the PC2 size, the OBJ sequence, updateObject, and two
// closed-form results (free fall, zero gravity). Arguments: <tests/data> <shared data> <tmp>.
"use strict";
const [dataDir, , tmpDir] = core.scriptArguments();

core.include("test_asserts.js");

core.makePath(tmpDir);
const grid = core.loadObject(dataDir + "/grid3x3.obj");
const before = core.objectInfo(grid);
const topRow = [12, 13, 14, 15];
const frames = 10, substeps = 4, vertices = 16;
const pc2 = tmpDir + "/grid.pc2";

const report = multirescloth.simulate(grid, {frames: frames, substeps: substeps, pins: topRow, output: pc2});

// Every field, with its type.
const types = {
  frames: "number", steps: "number", timeStep: "number", precomputeMs: "number", msPerFrame: "object",
  maxStretch: "number", meanRounds: "number", maxPenetration: "number", initialPenetration: "number", nonFinite: "boolean", cancelled: "boolean", output: "string",
  vertices: "number", freeVertices: "number", pinnedVertices: "number", hangingVertices: "number",
  springs: "object", perFrameMs: "array", operation: "string", source: "number", material: "string",
  objFiles: "array",
};
for (const [key, type] of Object.entries(types)) expectType(report[key], type, "report." + key);
for (const key of ["dynamics", "collision", "total", "limiter", "posing", "firstRound"])
  expectType(report.msPerFrame[key], "number", "msPerFrame." + key);
for (const key of ["stretch", "shear", "bend"]) expectType(report.springs[key], "number", "springs." + key);
expectEqual(report.perFrameMs.length, frames, "perFrameMs has one entry per frame");
// Every step takes at least one round and at most the integrator's 8.
if (!(report.meanRounds >= 1 && report.meanRounds <= 8)) throw new Error("meanRounds " + report.meanRounds);
report.perFrameMs.forEach((timing, frame) => {
  expectType(timing.dynamics, "number", "perFrameMs[" + frame + "].dynamics");
  expectType(timing.collision, "number", "perFrameMs[" + frame + "].collision");
});
if (report.resultId !== undefined) throw new Error("resultId without updateObject: " + report.resultId);
expectNear(report.msPerFrame.total, report.msPerFrame.dynamics + report.msPerFrame.collision, 1e-9, "total = dynamics + collision");
if (!(report.precomputeMs >= 0 && report.msPerFrame.dynamics >= 0)) throw new Error("negative timings");
// The parts lie within their wholes; a grid with no body poses nothing.
{
  const t = report.msPerFrame;
  if (!(t.limiter > 0 && t.limiter <= t.dynamics)) throw new Error("limiter " + t.limiter + " of dynamics " + t.dynamics);
  if (!(t.firstRound >= 0 && t.posing + t.firstRound <= t.collision)) throw new Error("parts of collision " + JSON.stringify(t));
  expectEqual(t.posing, 0, "posing without a body");
}

// Values.
expectEqual([report.operation, report.source, report.material], ["simulate", grid, "cotton"], "report header");
expectEqual([report.frames, report.steps, report.nonFinite, report.cancelled], [frames, frames * substeps, false, false],
            "frames and steps");
expectNear(report.timeStep, 1 / (30 * substeps), 1e-15, "timeStep = 1 / (fps * substeps)");
expectEqual([report.vertices, report.freeVertices, report.pinnedVertices, report.hangingVertices], [16, 12, 4, 0],
            "vertex classes");
// 24 edges, 2 diagonals in each of 9 faces, and two-step pairs: 8 along rows,
// 8 along columns, 4 + 4 along the diagonals.
expectEqual(report.springs, {bend: 24, shear: 18, stretch: 24}, "springs");
if (!(report.maxStretch > 0 && report.maxStretch < 0.05)) throw new Error("maxStretch " + report.maxStretch);
expectEqual(report.maxPenetration, 0, "no colliders, no penetration");

// The PC2 cache: 32-byte header, then frames x vertices x 3 float32.
expectEqual(report.output, pc2, "output");
if (!core.fileExists(pc2)) throw new Error("no PC2 at " + pc2);
expectEqual(core.fileSize(pc2), 32 + frames * vertices * 12, "PC2 size");
expectEqual(report.objFiles, [], "no OBJ sequence unless asked");

// lastReport() is the same report; the input is untouched and nothing was added.
expectEqual(multirescloth.lastReport(), report, "lastReport");
expectEqual(core.objectInfo(grid), before, "input object untouched");
expectEqual(core.objectList().length, 1, "no new object without updateObject");

// Other step counts and rates; no output: output is "".
const other = multirescloth.simulate(grid, {frames: 3, fps: 60, substeps: 2, iterations: 2, pins: topRow});
expectEqual([other.frames, other.steps, other.output], [3, 6, ""], "3 frames x 2 substeps, no output");
expectNear(other.timeStep, 1 / 120, 1e-15, "timeStep at 60 fps x 2");

// OBJ sequence and updateObject: the last frame becomes a new object.
const sequence = multirescloth.simulate(grid, {frames: 4, pins: topRow, objSequence: tmpDir + "/grid_frame",
                                               updateObject: true});
expectEqual(sequence.objFiles, [0, 1, 2, 3].map(k => tmpDir + "/grid_frame_000" + k + ".obj"), "objFiles");
for (const file of sequence.objFiles) if (!core.fileExists(file)) throw new Error("not written: " + file);
const frame3 = core.objectInfo(core.loadObject(sequence.objFiles[3]));
expectEqual([frame3.vertices, frame3.faces], [16, 9], "an OBJ frame has the mesh's vertices and faces");
expectType(sequence.resultId, "number", "resultId");
const simulated = core.objectInfo(sequence.resultId);
expectEqual([simulated.vertices, simulated.faces, simulated.hangingNodes], [16, 9, 0], "the new object's counts");
expectEqual(simulated.bbox.max[1], 3, "the pinned top row stays at y = 3");
if (!(simulated.bbox.min[1] < 0)) throw new Error("the sheet did not sag: " + JSON.stringify(simulated.bbox));
for (const corner of ["min", "max"])  // OBJ files keep 9 significant digits
  for (let axis = 0; axis < 3; ++axis)
    expectNear(frame3.bbox[corner][axis], simulated.bbox[corner][axis], 1e-7, "the last OBJ frame is the new object");
expectEqual(core.objectInfo(grid), before, "input object untouched by updateObject");

// Free fall without damping is the exact parabola: 0.5 g t^2 after t = 10 / 30 s.
const fall = multirescloth.simulate(grid, {frames: 10, material: {damping: 0}, updateObject: true});
expectEqual(fall.pinnedVertices, 0, "no pins");
const fallen = core.objectInfo(fall.resultId).bbox;
expectNear(fallen.min[1], -0.5 * 9.81 * (10 / 30) ** 2, 1e-9, "free-fall drop");
expectNear(fallen.max[1] - fallen.min[1], 3, 1e-9, "a falling sheet keeps its shape");

// Without gravity a pinned sheet at rest stays at rest.
const still = multirescloth.simulate(grid, {frames: 5, gravity: [0, 0, 0], pins: topRow, updateObject: true});
expectEqual(core.objectInfo(still.resultId).bbox, before.bbox, "zero gravity: at rest");
expectEqual(still.maxStretch, 0, "zero gravity: no stretch");

// Materials: presets and overrides.
for (const material of ["silk", "denim", {preset: "denim", damping: 1, stretchLimit: 0.02}, {bendStiffness: 0}]) {
  const run = multirescloth.simulate(grid, {frames: 2, pins: topRow, material: material});
  expectEqual([run.frames, run.nonFinite], [2, false], "material " + JSON.stringify(material));
}
print("simulate grid: ok");
