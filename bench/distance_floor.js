"use strict";
// The distance measure's noise floor for a `mrcloth pipeline` run: the
// high-resolution garment simulated again on each test motion with the
// pre-roll a little longer (1 ms by default), its distance to the
// pipeline's own high-resolution result; and every compared model re-run
// the same way, its distance beside the pipeline's. The motion is chaotic:
// where the floor, or a model's change, is as large as the gap between two
// models, "closer to the high-resolution result" does not tell them apart.
//
// Usage (from where the pipeline ran, as its options.json holds paths
// relative to there):
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

const optionsPath = out + "/stages/options.json";
if (!core.fileReadable(optionsPath)) throw new Error(optionsPath + " is not readable: expected a pipeline output folder");
const o = JSON.parse(core.readTextFile(optionsPath));
const required = (path, what) => {
  if (!core.fileReadable(path)) throw new Error(what + " " + path + " (from " + optionsPath + ") is not readable here: run from where the pipeline ran");
  return path;
};
// The body as the pipeline gives it (resources/scripts/pipeline.js).
const body = o.makehuman ? {type: o.body, obj: required(o.makehuman + "/base.obj", "the body"),
                            skeleton: required(o.makehuman + "/rigs/cmu_mb.mhskel", "the rig"),
                            weights: required(o.makehuman + "/rigs/default_weights.mhw", "the skin weights")}
                         : o.body;
const high = core.loadObject(required(out + "/meshes/high_modes.om", "the high-resolution mesh"));
const name = (path) => path.split("/").pop().replace(/\.bvh$/i, "");
core.makePath(out + "/floor");

// The model files as the pipeline names them (resources/scripts/pipeline.js).
const modelFile = (model) => model === "coarse" ? "meshes/coarse_modes.om"
                           : model.startsWith("uniform_L") ? "meshes/uniform_equal.om" : "meshes/" + model + ".om";
const ms = (x) => (1000 * x).toFixed(1);
print("Mean RMS distance to the pipeline's high-resolution result, mm: as the pipeline measured it, and with the " +
      "pre-roll " + ms(perturbation) + " ms longer (the high-resolution garment itself first: the noise floor).\n");
print("| motion | high (floor) | models: pipeline -> pre-roll longer |");
print("|---|---|---|");
for (const motionPath of o.test) {
  const motion = name(motionPath);
  const reference = out + "/caches/high_" + motion + ".pc2";
  const comparePath = out + "/stages/compare-" + motion + ".json";
  if (!core.fileReadable(reference) || !core.fileReadable(comparePath)) {
    print("| " + motion + " | not compared by the pipeline (" + comparePath + ") | |");
    continue;
  }
  const options = {motion: {path: required(motionPath, "the motion"), units: o.motionUnits}, body: body, place: o.place,
                   preroll: o.preroll + perturbation, frames: o.testFrames, fps: o.fps, material: o.material};
  // Simulates `id` with the longer pre-roll and measures it against the pipeline's high result.
  const rerun = (id, model) => {
    const cache = out + "/floor/" + model + "_" + motion + ".pc2";
    multirescloth.simulate(id, Object.assign({}, options, {output: cache}));
    return multirescloth.compareResults(id, cache, high, reference).meanRms;
  };
  const floor = rerun(high, "high");
  if (perturbation === 0 && floor !== 0) differences.push(motion + ": high is " + ms(floor) + " mm from itself");
  const models = JSON.parse(core.readTextFile(comparePath)).rows.map((row) => {
    const id = core.loadObject(required(out + "/" + modelFile(row.model), "the model"));
    const again = rerun(id, row.model);
    core.deleteObject(id);
    if (perturbation === 0 && Math.abs(again - row.meanRms) > 1e-12)
      differences.push(motion + ": " + row.model + " " + again + " m, the pipeline measured " + row.meanRms);
    return row.model + " " + ms(row.meanRms) + " -> " + ms(again);
  });
  print("| " + motion + " | " + ms(floor) + " | " + models.join(", ") + " |");
}
if (perturbation === 0) {
  if (differences.length > 0) throw new Error("the re-runs do not reproduce the pipeline: " + differences.join("; "));
  print("\nperturbation 0: every re-run reproduces the pipeline's distances");
}
