// The shared ankle-length skirt on CMU 07_06 asks for more girth near its
// hem than it has (bench_fit: +35 %), so simulate warns before the run,
// naming the level, and reports every level in `fit` (checked by
// run_and_check.cmake: the [warn] line), unless told not to (fitWarning:
// false, as the pipeline does for every model after a motion's first; the
// report has it either way). Capsules fitted to the MakeHuman
// body and 20 frames keep it short. Skipped (exit 77) without ../shared/data.
// Arguments: <tests/data> <shared data> <tmp>.
"use strict";
const [, sharedDir] = core.scriptArguments();
core.include("test_asserts.js");
const {garment, clip, body} = sharedMakeHuman(sharedDir, "skirthelper.obj", "capsules");
const report = multirescloth.simulate(core.loadObject(garment, {units: "dm"}), {
  motion: {path: clip, units: "cmu"}, body: body, place: "makehuman", preroll: 0.2, frames: 20});
const levels = report.fit.levels;
expectEqual([levels.length, report.fit.stretchLimit], [8, 0.03], "fit levels and cotton's limit");
// The waist fits; the lower half does not.
if (!(levels[0].demand < 0.03)) throw new Error("the waist level asks for " + levels[0].demand);
if (!(report.fit.largestDemand > 0.1)) throw new Error("largest demand " + report.fit.largestDemand);
const worst = levels.findIndex(l => l.demand === report.fit.largestDemand);
if (!(worst >= 4)) throw new Error("the most demanding level is " + (worst + 1) + " of 8; expected the lower half");
for (const l of levels)
  if (!(l.bodyGirth > 0 && l.garmentGirth > 0 && l.frame >= 0 && l.frame < 20)) throw new Error(JSON.stringify(l));
print("fit warning: largest demand " + (100 * report.fit.largestDemand).toFixed(0) + " % at level " + (worst + 1));
// fitWarning: false keeps the log quiet (run_and_check: one warning in all),
// and the report has the fit all the same.
const quiet = multirescloth.simulate(core.loadObject(garment, {units: "dm"}), {
  motion: {path: clip, units: "cmu"}, body: body, place: "makehuman", preroll: 0.2, frames: 20, fitWarning: false});
expectEqual([quiet.fit.largestDemand, quiet.fit.levels.length], [report.fit.largestDemand, 8], "the quiet run's fit");
print("quiet run: fit reported");
// The shared knee-length skirt: its waistband is 5 cm lower at the front
// than at the back and its hem 21 cm longer at the back, so the levels
// lie between the waistband's lowest point and the hem's highest, where
// each cuts the whole tube. There it fits the walk (bench_fit: -2 to -4 %
// on 07_06) and no warning is given. Measured over the whole skirt, its
// top and bottom levels cut only part of it, and the hull of that arc
// asked for 23 and 29 % more girth than it has.
{
  const knee = sharedMakeHuman(sharedDir, "female_elegantsuit01_skirt_on_base.obj", "capsules");
  const fit = multirescloth.simulate(core.loadObject(knee.garment, {units: "dm"}), {
    motion: {path: clip, units: "cmu"}, body: body, place: "makehuman", preroll: 0.2, frames: 20}).fit;
  expectEqual(fit.levels.length, 8, "the knee-length skirt's levels");
  expectAtMost(fit.largestDemand, 0.03, "the knee-length skirt's largest demand");
  print("knee-length skirt: largest demand " + (100 * fit.largestDemand).toFixed(0) + " %");
}
