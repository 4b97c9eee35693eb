// The shared trousers start 4.3 mm inside capsules fitted to the MakeHuman
// body (modelled that close; the first step pushes them out): simulate
// warns, naming the depth, unless fitWarning is false, as the pipeline
// sets it for every model after a motion's first (run_and_check.cmake:
// one warning in all). The report has the depth either way. Skipped (exit
// 77) without ../shared/data. Arguments: <tests/data> <shared data>.
"use strict";
const [, sharedDir] = core.scriptArguments();
core.include("test_asserts.js");
const {garment, clip, body} = sharedMakeHuman(sharedDir, "male_casualsuit04_pants_on_base.obj", "capsules");
const run = (fitWarning) => multirescloth.simulate(core.loadObject(garment, {units: "dm"}), {
  motion: {path: clip, units: "cmu"}, body: body, place: "makehuman", preroll: 0.05, frames: 1, fitWarning: fitWarning});
const told = run(true), quiet = run(false);
expectAtLeast(told.preroll.initialPenetration, 0.003, "the trousers start inside the capsules");
expectEqual(quiet.preroll.initialPenetration, told.preroll.initialPenetration, "the quiet run's report");
print("initial penetration: " + (1000 * told.preroll.initialPenetration).toFixed(1) + " mm, reported by both runs");
