// Warnings before a run on a character that would tear for its motion's
// sake (run_and_check checks them): a pre-roll too short for the legs' way
// from the rest pose to the motion's first frame (preroll_leg_speed above
// 8 m/s; the default skirt on the new walk: none at 0.5 s, 23 m/s at 0.02
// s, in one step at 0), and a glitch in the clip within the frames run (the
// root 1 m off for one frame: 120 m/s), which motionInfo's fastestLegSpeed
// finds too. Arguments: <tmp>.
"use strict";
core.include("test_asserts.js");
const [tmpDir] = core.scriptArguments();
core.makePath(tmpDir);
const skirt = core.loadObject(core.resourcePath() + "/garments/default_skirt.obj");
const walk = core.resourcePath() + "/characters/walk_new.bvh";
const run = (clip, preroll, frames) => multirescloth.simulate(skirt, {
  motion: {path: clip}, body: "capsules", place: "firstFrame", preroll: preroll, frames: frames, fitWarning: false});
// Each warning is in the run's report too, for a batch script to act on.
const warnings = [0.5, 0.02, 0].map((preroll) => run(walk, preroll, 1).warnings);
expectEqual(warnings.map((w) => w.length), [0, 1, 1], "the reports' warnings");
expectEqual([warnings[1][0].includes("the pre-roll of 0.02 s moves the legs"), warnings[2][0].includes("in one step")],
            [true, true], "the reports' warnings, word for word as logged: " + JSON.stringify(warnings));

// The same walk with its root 1 m along x at frame 60 (from 0, the T-pose).
const lines = core.readTextFile(walk).split("\n");
const motionAt = lines.findIndex((line) => line.trim() === "MOTION");
const row = motionAt + 3 + 60;  // MOTION, Frames:, Frame Time:, then frame 0
const values = lines[row].trim().split(/\s+/).map(Number);
values[0] += 1.0;
lines[row] = values.join(" ");
const glitch = tmpDir + "/walk_glitch.bvh";
core.writeTextFile(glitch, lines.join("\n"));
const fastest = multirescloth.motionInfo({path: glitch}).fastestLegSpeed;
expectEqual([fastest.frame === 59 || fastest.frame === 60, fastest.speed > 110, fastest.speed < 130], [true, true, true],
            "the glitch found: " + JSON.stringify(fastest));
expectAtMost(multirescloth.motionInfo({path: walk}).fastestLegSpeed.speed, 8, "the clean walk's fastest leg joint, m/s");
expectEqual(run(glitch, 0.5, 1).warnings, [], "frames 1-5 of the run: the glitch is later, no warning");
expectEqual(run(glitch, 0.5, 30).warnings.length, 1, "a second: it is run through");
print("motion warnings: ok");
