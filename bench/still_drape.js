"use strict";
// How far each model of a `mrcloth pipeline` run drapes from the
// high-resolution garment when nothing moves: every compared model and the
// high-resolution mesh are simulated on the pipeline's first test motion
// held at its first frame (the same body, pre-roll and settings as the
// pipeline's test runs), and each one's distance to the high-resolution
// result is measured as the pipeline measures it, with how deep its faces'
// centres sink into the body between their corners (only vertices
// collide). A still body takes the motion's chaos out of "closer to the
// high-resolution result": what is left is how differently the meshes hang.
//
// Usage (from where the pipeline ran, as its report holds paths as given):
//   build/bin/mrcloth -b bench/still_drape.js -- <pipeline output folder> [alphaBend [alpha [options]]]
// alphaBend / alpha: the stiffness-per-level exponents (default: the
// pipeline's, i.e. the plugin's defaults; "-" keeps it), to see how they
// move the drape. options: more multirescloth.simulate options as a JSON
// object, for every model and the high-resolution mesh alike, e.g.
// '{"limiterMassExponent": 1}'.
// Writes <output>/still/<motion>_still.bvh and <output>/still/<model>.pc2
// (+ .obj) and prints a table.

const args = core.scriptArguments();
if (args.length < 1) throw new Error("usage: still_drape.js <pipeline output folder> [alphaBend [alpha [options]]]");
const out = args[0];
const stiffness = {};
if (args.length > 1 && args[1] !== "-") stiffness.alphaBend = Number(args[1]);
if (args.length > 2 && args[2] !== "-") stiffness.alpha = Number(args[2]);
for (const key of Object.keys(stiffness))
  if (!Number.isFinite(stiffness[key])) throw new Error(key + " must be a number, got " + args[key === "alphaBend" ? 1 : 2]);

core.include("pipeline_report.js");
const report = readPipelineReport(out);
const motionPath = report.options.test[0];
const motion = motionPath.split("/").pop().replace(/\.bvh$/i, "");

// The motion with every frame replaced by its second (the first is the
// T-pose CMU clips start with; with skipFirst it is skipped anyway): the
// body stands as the test walk starts, for the whole run.
const held = (text) => {
  const lines = text.split(/\r?\n/);
  const at = lines.findIndex((line) => /^\s*Frame Time:/i.test(line));
  if (at < 0) throw new Error(motionPath + ": no 'Frame Time:' line; expected a BVH motion");
  const frames = lines.slice(at + 1).filter((line) => line.trim().length > 0);
  if (frames.length < 2) throw new Error(motionPath + ": " + frames.length + " frame(s); expected at least 2");
  return lines.slice(0, at + 1).concat(frames.map(() => frames[1])).join("\n") + "\n";
};
core.makePath(out + "/still");
const stillPath = out + "/still/" + motion + "_still.bvh";
core.writeTextFile(stillPath, held(core.readTextFile(motionPath)));

let extra = {};
if (args.length > 3) {
  try {
    extra = JSON.parse(args[3]);
  } catch (e) {
    throw new Error("options must be a JSON object of simulate options, got " + args[3] + " (" + e.message + ")");
  }
  if (extra === null || typeof extra !== "object" || Array.isArray(extra))
    throw new Error("options must be a JSON object of simulate options, got " + args[3]);
}
const settings = Object.assign({}, report.testSettings, stiffness, extra,
                               {motion: {path: stillPath, units: report.options.motionUnits}});
const rows = report.table3.filter((row) => row.motion === motion);
const high = rows.find((row) => row.model === "high");
if (!high) throw new Error(out + "/report.json: no high-resolution run on " + motion);
const simulate = (row) => {
  const id = core.loadObject(out + "/" + row.modelFile);
  const cache = out + "/still/" + row.model + ".pc2";
  const report = multirescloth.simulate(id, Object.assign({}, settings, {output: cache}));
  return {id, cache, faceDepth: report.maxFaceDepth};
};
const reference = simulate(high);
const mm = (x) => (1000 * x).toFixed(1);
print("Held at the first frame of " + motion + " (" + settings.frames + " frames after a " + settings.preroll +
      " s pre-roll; alphaBend " + (stiffness.alphaBend ?? "default") + ", alpha " + (stiffness.alpha ?? "default") +
      "): distance to the high-resolution result, mm, and the pipeline's on the walk.\n");
print("| model | vertices | mean RMS | last frame RMS | top-mode bending kept | deepest face centre | on the walk: mean RMS |");
print("|---|---:|---:|---:|---:|---:|---:|");
for (const row of rows) {
  if (row === high) continue;
  const run = simulate(row);
  const c = multirescloth.compareResults(run.id, run.cache, reference.id, reference.cache);
  const walk = report.detail.find((d) => d.motion === motion && d.model === row.model);
  print("| " + row.model + " | " + row.vertices + " | " + mm(c.meanRms) + " | " + mm(c.rmsPerFrame[c.rmsPerFrame.length - 1]) +
        " | " + (100 * c.wrinkleKeptRegion).toFixed(0) + " % | " + mm(run.faceDepth) + " | " + (walk ? mm(walk.meanRms) : "-") + " |");
  core.deleteObject(run.id);
}
print("| high | " + high.vertices + " | 0.0 | 0.0 | 100 % | " + mm(reference.faceDepth) + " | 0.0 |");
core.deleteObject(reference.id);
