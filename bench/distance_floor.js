"use strict";
// The distance measure's noise floor for a `mrcloth pipeline` run: the
// high-resolution garment simulated again on each test motion with the
// pre-roll a little longer (1 ms by default), its distance to the
// pipeline's own high-resolution result; and every compared model re-run
// the same way, its distance beside the pipeline's. The motion is chaotic:
// where the floor, or a model's change, is as large as the gap between two
// models, "closer to the high-resolution result" does not tell them apart.
//
// Usage (from where the pipeline ran, as its report holds paths as given):
//   build/bin/mrcloth -b bench/distance_floor.js -- <pipeline output folder> [perturbation seconds = 0.001]
// Writes <output>/floor/<model>_<motion>.pc2 (+ .obj) and prints a table.
// A perturbation of 0 checks that the re-runs are the pipeline's own: every
// distance must come out as the pipeline measured it (the floor 0), else
// the script fails.

const args = core.scriptArguments();
if (args.length < 1) throw new Error("usage: distance_floor.js <pipeline output folder> [perturbation seconds]");
const out = args[0];
const perturbation = args.length > 1 ? Number(args[1]) : 0.001;
if (!(perturbation >= 0)) throw new Error("the perturbation must be a number of seconds >= 0, got " + args[1]);
const differences = [];  // with perturbation 0: what did not reproduce

core.include("pipeline_report.js");
const report = readPipelineReport(out);
const ms = (x) => (1000 * x).toFixed(1);
const name = (path) => path.split("/").pop().replace(/\.bvh$/i, "");

print("Mean RMS distance to the pipeline's high-resolution result, mm: as the pipeline measured it, and with the " +
      "pre-roll " + ms(perturbation) + " ms longer (the high-resolution garment itself first: the noise floor).\n");
print("| motion | high (floor) | models: pipeline -> pre-roll longer |");
print("|---|---|---|");
core.makePath(out + "/floor");
for (const motionPath of report.options.test) {
  const motion = name(motionPath);
  const high = report.table3.find((row) => row.motion === motion && row.model === "high");
  const compared = report.detail.filter((row) => row.motion === motion);
  if (!high || compared.length === 0) {
    print("| " + motion + " | not compared by the pipeline | |");
    continue;
  }
  const reference = out + "/" + high.cache;
  const highId = core.loadObject(out + "/" + high.modelFile);
  const settings = Object.assign({}, report.testSettings, {motion: {path: motionPath, units: report.options.motionUnits},
                                                           preroll: report.testSettings.preroll + perturbation});
  // Simulates model `row` with the longer pre-roll; its distance to the pipeline's high result.
  const rerun = (row) => {
    const id = row === high ? highId : core.loadObject(out + "/" + row.modelFile);
    const cache = out + "/floor/" + row.model + "_" + motion + ".pc2";
    multirescloth.simulate(id, Object.assign({}, settings, {output: cache}));
    const distance = multirescloth.compareResults(id, cache, highId, reference).meanRms;
    if (id !== highId) core.deleteObject(id);
    return distance;
  };
  const floor = rerun(high);
  if (perturbation === 0 && floor !== 0) differences.push(motion + ": high is " + ms(floor) + " mm from itself");
  const models = compared.map((row) => {
    const again = rerun(report.table3.find((r) => r.motion === motion && r.model === row.model));
    if (perturbation === 0 && Math.abs(again - row.meanRms) > 1e-12)
      differences.push(motion + ": " + row.model + " " + again + " m, the pipeline measured " + row.meanRms);
    return row.model + " " + ms(row.meanRms) + " -> " + ms(again);
  });
  core.deleteObject(highId);
  print("| " + motion + " | " + ms(floor) + " | " + models.join(", ") + " |");
}
if (perturbation === 0) {
  if (differences.length > 0) throw new Error("the re-runs do not reproduce the pipeline: " + differences.join("; "));
  print("\nperturbation 0: every re-run reproduces the pipeline's distances");
}
