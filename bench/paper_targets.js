// Issue 7's targets, read off finished pipeline runs (report.json): for every
// multi-resolution mesh on every test walk,
//   cost:   at or under 35 % of the high-resolution mesh's ms per frame (paper 33 %)
//   speed:  at or under 33 ms per frame
//   closer: mean RMS distance to the high-resolution result below the
//           equal-size uniform mesh's
//   detail: at least 90 % of the high-resolution bending energy kept in the
//           top-mode region
// Motions named like a squat are the paper's stated limit: shown, not judged.
// A result in which an edge at least doubled in length and opened more than
// 1 cm (maxTearOpening) is torn: cloth parted around a limb, whose
// distances and energies measure the tear, so it meets no target; and a
// torn high-resolution (or equal-size uniform) result voids the checks
// measured against it. Relative stretch alone is no gate: on edges shorter
// than the body's 4 mm thickness a collision push of a few millimetres is
// 100-400 % (the trousers' 2.3 mm edges).
// The pipeline runs on one core by default (--threads 1), so its times are
// one-core times; a report run with more threads is refused.
//
// Usage: mrcloth -q -b bench/paper_targets.js -- OUT_DIR [OUT_DIR ...]
//   (bench/paper_targets.sh runs the pipeline first when asked to)
"use strict";

const TARGETS = {costShare: 0.35, msPerFrame: 33.0, detailKept: 0.90};
const LIMIT_MOTION = /squat/i;
const TORN_OPENING = 0.01;  // metres
const DEFAULT_STEP_RATE = 120;  // simulate's steps per second when a run gives no stepRate

function fixed(value, digits) {
  return value === undefined || value === null || !isFinite(value) ? "-" : Number(value).toFixed(digits);
}

function readReport(folder) {
  const path = folder + "/report.json";
  if (!core.fileExists(path)) throw new Error(path + " does not exist; expected a finished `mrcloth pipeline` run there");
  let report;
  try {
    report = JSON.parse(core.readTextFile(path));
  } catch (error) {
    throw new Error(path + ": not JSON (" + error.message + "); expected the pipeline's report.json");
  }
  for (const key of ["table3", "detail", "uniformEqual", "garment"])
    if (report[key] === undefined) throw new Error(path + ": no \"" + key + "\"; expected the pipeline's report.json");
  const threads = report.testSettings && report.testSettings.threads !== undefined ? report.testSettings.threads : 1;
  if (threads !== 1)
    throw new Error(path + ": run with --threads " + threads + "; the targets are one core's times: re-run the " +
                    "pipeline with --threads 1");
  for (const row of report.table3)
    if (typeof row.maxTearOpening !== "number")
      throw new Error(path + ": " + row.model + " on " + row.motion + " has no maxTearOpening; expected a report " +
                      "from a pipeline that measures it (re-run the pipeline without --resume)");
  return report;
}

function rowOf(rows, motion, model) {
  return rows.find((row) => row.motion === motion && row.model === model);
}

function torn(row) {
  return row !== undefined && row.maxTearOpening > TORN_OPENING;
}

/// One line per (motion, multi-resolution mesh), and the checks it passed.
function judge(folder, report) {
  const lines = [];
  let met = 0, judged = 0;
  const equalName = "uniform_L" + report.uniformEqual.level;
  const motions = report.table3.map((row) => row.motion).filter((m, k, all) => all.indexOf(m) === k);
  const garment = report.garment.file.split("/").pop();
  for (const motion of motions) {
    const high = rowOf(report.table3, motion, "high");
    const equal = rowOf(report.detail, motion, equalName);
    const highTorn = torn(high);
    const equalTorn = torn(rowOf(report.table3, motion, equalName));
    const limit = LIMIT_MOTION.test(motion);
    for (const run of report.table3.filter((row) => row.motion === motion && row.model.startsWith("multires_"))) {
      const detail = rowOf(report.detail, motion, run.model) || {};
      const share = high ? run.totalMs / high.totalMs : NaN;
      const checks = [
        ["cost", share <= TARGETS.costShare],
        ["speed", run.totalMs <= TARGETS.msPerFrame],
        ["closer", equal !== undefined && detail.meanRms < equal.meanRms],
        ["detail", detail.wrinkleKeptRegion >= TARGETS.detailKept],
      ];
      const runTorn = torn(run);
      // What a tear voids: everything of a torn run; what is measured
      // against a torn high (closer, detail) or uniform result (closer).
      const voided = (name) => runTorn || (highTorn && (name === "closer" || name === "detail")) ||
                               (equalTorn && name === "closer");
      for (const check of checks) check[1] = check[1] && !voided(check[0]);
      const passed = checks.filter((check) => check[1]).map((check) => check[0]);
      const failed = checks.filter((check) => !check[1]).map((check) => check[0]);
      if (!limit) {
        judged += checks.length;
        met += passed.length;
      }
      lines.push("| " + [garment, motion, run.model, run.vertices, fixed(run.totalMs, 1), fixed(100 * share, 1) + " %",
                         fixed(1000 * detail.meanRms, 1) + " / " + (equal ? fixed(1000 * equal.meanRms, 1) : "-"),
                         fixed(100 * detail.wrinkleKeptRegion, 1) + " %",
                         fixed(100 * run.maxStretch, 0) + " % / " + fixed(1000 * run.maxTearOpening, 1) + " mm",
                         limit ? "limit motion: not judged" :
                         runTorn ? "torn (an edge doubled and opened > " + 1000 * TORN_OPENING + " mm): none met" :
                                 (failed.length === 0 ? "all met" : "missed: " + failed.join(", ")) +
                                 (highTorn ? " (high torn: closer, detail void)" : equalTorn ? " (uniform torn: closer void)" : "")]
                            .join(" | ") + " |");
    }
  }
  return {lines: lines, met: met, judged: judged, folder: folder};
}

const folders = core.scriptArguments();
if (folders.length === 0) throw new Error("paper_targets: name at least one pipeline output folder");
const reports = folders.map(readReport);  // every report checked before anything is printed
print("Issue 7 targets per multi-resolution mesh and test motion: cost <= " + 100 * TARGETS.costShare +
      " % of high, speed <= " + TARGETS.msPerFrame + " ms/frame (one core), closer to high than the equal-size uniform " +
      "mesh (mean RMS), detail >= " + 100 * TARGETS.detailKept + " % of high's bending energy in the top-mode region.");
print("");
print("| garment | motion | mesh | vertices | ms/frame | % of high | RMS to high mm (uniform) | detail kept | max stretch / tear opening | targets |");
print("|---|---|---|---:|---:|---:|---:|---:|---:|---|");
let met = 0, judged = 0;
const perGarment = [];
for (let k = 0; k < folders.length; ++k) {
  const result = judge(folders[k], reports[k]);
  for (const line of result.lines) print(line);
  met += result.met;
  judged += result.judged;
  perGarment.push(reports[k].garment.file.split("/").pop() + " " + result.met + " of " + result.judged);
}
print("");
print("targets met: " + met + " of " + judged + " checks on the test walks");
// The issue names the skirt for cost and speed; every garment given is
// judged by all four, and each garment's count is said apart.
if (folders.length > 1) print("per garment: " + perGarment.join(", "));
// The step rate moves every time and distance (README, Half the steps):
// say it, and say when it is not the mocap rate the defaults step at.
const rates = reports.map((report) => {
  const settings = report.testSettings || {};
  return settings.stepRate !== undefined ? settings.stepRate : DEFAULT_STEP_RATE;
});
print("steps per second: " + reports.map((report, k) => report.garment.file.split("/").pop() + " " + rates[k]).join(", ") +
      (rates.some((rate) => rate !== DEFAULT_STEP_RATE) ? " (the defaults step at " + DEFAULT_STEP_RATE + ", the mocap rate)" : ""));
