// Checks a pipeline output folder (and, given a second one, that both runs
// gave the same numbers). Used by pipeline_test.sh.
//
// mrcloth -b pipeline_check.js -- <out> [<other out>]
"use strict";
core.include("test_asserts.js");
const [out, other] = core.scriptArguments();

function check(condition, what) {
  if (!condition) throw new Error("pipeline check failed: " + what + " (in " + out + ")");
}

const report = JSON.parse(core.readTextFile(out + "/report.json"));
const options = report.options;

// Every table field, for every row.
for (const key of ["vertices", "frames", "seconds", "msPerFrame", "maxStretch", "maxPenetration", "motion"])
  check(report.table1Instance[key] !== undefined, "table1Instance." + key);
for (const key of ["dynamics", "collision", "total"])
  check(typeof report.table1Instance.msPerFrame[key] === "number", "table1Instance.msPerFrame." + key);
expectEqual(report.table1Instance.frames, options.instanceFrames, "instance frames");
// --step-rate reaches the runs (simulate's default without it: 120 per second).
const stepRate = options.stepRate === undefined ? 120 : options.stepRate;
expectEqual(report.table1Instance.stepRate, stepRate, "instance steps per second");
expectEqual(report.table2Refinement.length, 1 + options.delta.length, "table 2 rows");
for (const row of report.table2Refinement)
  for (const key of ["model", "vertices", "milliseconds", "verticesPerLevel"])
    check(row[key] !== undefined, "table2Refinement[" + row.model + "]." + key);
const models = ["coarse"].concat(options.delta.map((d) => "multires_d" + String(d).replace(".", "p")), ["high"]);
if (report.uniformEqual.level > 0 && report.uniformEqual.level < options.levels)
  models.push("uniform_L" + report.uniformEqual.level);
expectEqual(report.table3.length, models.length * options.test.length, "table 3 rows");
for (const row of report.table3) {
  for (const key of ["motion", "model", "vertices", "dynamicsMs", "collisionMs", "totalMs", "maxStretch",
                     "maxPenetration", "cache"])
    check(row[key] !== undefined, "table3[" + row.model + ", " + row.motion + "]." + key);
  check(Math.abs(row.totalMs - row.dynamicsMs - row.collisionMs) <= 1e-6 * Math.max(1, row.totalMs),
        row.model + ": total = dynamics + collision");
  check(row.maxStretch < 0.5 && row.maxPenetration < 0.01, row.model + " on " + row.motion + " stays sane");
}
expectEqual(report.table3.map((row) => row.model).slice(0, models.length), models, "models");
// Detail: every model but the high one, per test motion; the high result against itself would be 0.
expectEqual(report.detail.length, (models.length - 1) * options.test.length, "detail rows");
for (const row of report.detail) {
  for (const key of ["motion", "model", "vertices", "meanRms", "meanP95", "maxDistance", "wrinkleKept",
                     "wrinkleKeptRegion", "regionMode", "regionPoints", "rmsPerFrame"])
    check(row[key] !== undefined, "detail[" + row.model + ", " + row.motion + "]." + key);
  check(row.model !== "high", "no detail row for the reference itself");
  check(row.meanRms > 0 && row.meanRms <= row.maxDistance && row.meanP95 <= row.maxDistance,
        row.model + ": 0 < RMS, p95 <= max");
  expectEqual(row.rmsPerFrame.length, options.testFrames, row.model + ": RMS per frame");
}
expectEqual(report.modes.sizes.length, options.modes, "modes");
expectEqual(report.modes.sizes.reduce((a, b) => a + b, 0), report.table1Instance.vertices, "mode sizes sum");

// The files the report names exist, and the caches hold what it says.
for (const image of report.previews) check(core.fileExists(out + "/" + image.file), "preview " + image.file);
check(core.fileExists(out + "/report.md"), "report.md");
const markdown = core.readTextFile(out + "/report.md");
for (const heading of ["## Instance (Table 1)", "## Refinement (Table 2)", "## Test motions (Table 3)",
                       "## Detail against the high-resolution result", "## Pictures"])
  check(markdown.indexOf(heading) >= 0, "report.md has " + heading);
for (const row of report.table3) {
  const cache = out + "/" + row.cache;
  const rest = cache.replace(/\.pc2$/, ".obj");
  check(core.fileExists(rest), "rest mesh " + rest);
  // The cache animates its rest mesh (same vertex count) over the test's frames;
  // the model's own mesh reads it (the rest OBJ has polygons the loader would split).
  const restVertices = core.readTextFile(rest).split("\n").filter((line) => line.startsWith("v ")).length;
  expectEqual(restVertices, row.vertices, rest + " vertices");
  const model = core.loadObject(out + "/meshes/" + (row.model === "coarse" ? "coarse_modes" :
                                                   row.model === "high" ? "high_modes" :
                                                   row.model.startsWith("uniform_L") ? "uniform_equal" : row.model) + ".om");
  const read = multirescloth.extractModes(model, cache, {clusters: 1});
  expectEqual(read.frames, options.testFrames, cache + " frames");
  core.deleteObject(model);
}
for (const folder of ["meshes", "caches", "previews", "plots", "stages"])
  check(core.fileExists(out + "/" + folder), folder);

// Two runs with the same options give the same numbers (times aside), on
// any number of threads.
function numbers(r) {
  return {
    instance: [r.table1Instance.vertices, r.table1Instance.frames, r.table1Instance.maxStretch,
               r.table1Instance.maxPenetration],
    refinement: r.table2Refinement.map((row) => [row.model, row.vertices, row.hangingNodes, row.verticesPerLevel]),
    modes: [r.modes.sizes, r.modes.centroids, r.modes.coarseVerticesPerMode],
    runs: r.table3.map((row) => [row.motion, row.model, row.vertices, row.maxStretch, row.maxPenetration]),
    detail: r.detail.map((row) => [row.motion, row.model, row.meanRms, row.meanP95, row.wrinkleKept,
                                   row.wrinkleKeptRegion]),
  };
}
if (other) {
  const second = JSON.parse(core.readTextFile(other + "/report.json"));
  const withoutThreads = (o) => Object.assign({}, o, {threads: undefined});
  expectEqual(withoutThreads(second.options), withoutThreads(options), "options of both runs");
  expectEqual(numbers(second), numbers(report), "numbers of " + other + " against " + out);
}
print("pipeline check: ok (" + report.table3.length + " runs, stages run " + report.stages.ran.length +
      ", resumed " + report.stages.skipped.length + ")");
