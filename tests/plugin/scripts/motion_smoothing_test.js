// motion.smoothing and the jitter warning: raw capture noise on the
// embedded walk's joint angles is measured by motionInfo's legJitter and
// warned of before a run, with a smoothing that takes it out; smoothed by
// it, the run does not warn. The option's bad values are refused by name.
// Arguments: <tests/data> <shared data> <tmp>.
"use strict";
const [, , tmpDir] = core.scriptArguments();
core.include("test_asserts.js");
core.makePath(tmpDir);

// The embedded walk with a deterministic "noise" of up to 1 degree on every
// rotation channel of every frame (a linear congruential sequence).
const walk = core.resourcePath() + "/characters/walk_new.bvh";
const [hierarchy, motion] = core.readTextFile(walk).split("MOTION");
const rotation = [];
const channelLines = /CHANNELS\s+(\d+)((?:[ \t]+[A-Za-z]+)*)/g;
for (let match; (match = channelLines.exec(hierarchy)) !== null;)
  for (const name of match[2].trim().split(/\s+/).slice(0, Number(match[1]))) rotation.push(/rotation/.test(name));
let seed = 12345;
const noise = () => {
  seed = (Math.imul(seed, 1103515245) + 12345) >>> 0;
  return (seed / 4294967296 - 0.5) * 2.0;  // -1..1 degrees
};
const lines = motion.trim().split("\n");
const data = lines.slice(2).map((row) =>
    row.trim().split(/\s+/).map((value, k) => rotation[k] ? (Number(value) + noise()).toFixed(6) : value).join(" "));
const jittery = tmpDir + "/walk_jittery.bvh";
core.writeTextFile(jittery, hierarchy + "MOTION\n" + lines[0] + "\n" + lines[1] + "\n" + data.join("\n") + "\n");

const clean = multirescloth.motionInfo({path: walk}).legJitter;
const raw = multirescloth.motionInfo({path: jittery}).legJitter;
const smoothed = multirescloth.motionInfo({path: jittery, smoothing: 0.02}).legJitter;
expectAtMost(clean, 100, "the embedded walk's leg jitter (m/s^2)");
expectAtLeast(raw, 200, "the jittery walk's leg jitter");
expectAtMost(smoothed, 100, "the jittery walk's leg jitter smoothed by 0.02 s");
expectEqual(multirescloth.motionInfo({path: walk, smoothing: 0}).legJitter, clean, "smoothing 0");

// A run on the jittery walk warns, naming the smoothing that would do; with it, no jitter warning.
const skirt = core.loadObject(core.resourcePath() + "/garments/default_skirt.obj");
const warned = multirescloth.simulate(skirt, {motion: {path: jittery}, frames: 2, preroll: 0.1}).warnings
                   .filter((line) => line.includes("jitter ("));
expectEqual(warned.length, 1, "jitter warnings on the raw clip");
const suggested = /option 'motion\.smoothing' ([0-9.]+) s \(a Gaussian in time\) takes it out/.exec(warned[0]);
if (!suggested) throw new Error("the warning names no smoothing: " + warned[0]);
if (!warned[0].includes("walk_jittery.bvh")) throw new Error("the warning names no clip: " + warned[0]);
const calm = multirescloth.simulate(skirt, {motion: {path: jittery, smoothing: Number(suggested[1])}, frames: 2,
                                            preroll: 0.1});
expectEqual(calm.warnings.filter((line) => line.includes("jitter (")), [], "jitter warnings once smoothed");
expectEqual(multirescloth.simulate(skirt, {motion: walk, frames: 2, preroll: 0.1}).warnings
                .filter((line) => line.includes("jitter (")), [], "jitter warnings on the clean walk");

// Bad values, named.
expectThrows(() => multirescloth.motionInfo({path: walk, smoothing: -0.01}), "ArgumentError",
             "option 'motion.smoothing' must be a number >= 0, got the number -0.01");
expectThrows(() => multirescloth.motionInfo({path: walk, smoothing: 2}), "ArgumentError",
             "option 'motion.smoothing' must be at most 1 s", "got 2");
expectThrows(() => multirescloth.simulate(skirt, {motion: {path: walk, smoothing: "a little"}, frames: 2}),
             "ArgumentError", "option 'motion.smoothing'");
print("motion smoothing: ok (" + checked + " errors checked)");
