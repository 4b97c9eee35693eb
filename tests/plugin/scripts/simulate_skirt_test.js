// The embedded default skirt pinned at its waist ("top") over a sphere that
// pushes its front out: no penetration, bounded stretch, finite; and the
// sphere really changes the motion. Arguments: <tests/data> <shared data> <tmp>.
"use strict";
const [, , tmpDir] = core.scriptArguments();

core.include("test_asserts.js");

core.makePath(tmpDir);
const skirt = core.loadObject(core.resourcePath() + "/garments/default_skirt.obj");
const info = core.objectInfo(skirt);
// Waist at y = 1.02 m, front at z ~ 0.13 m near y = 0.8: the sphere reaches
// z = 0.15 there, so it starts inside the cloth and pushes it out.
const sphere = {type: "sphere", center: [0, 0.8, 0.05], radius: 0.1};
const frames = 20;
const withSphere = tmpDir + "/skirt_sphere.pc2", without = tmpDir + "/skirt_free.pc2";

const report = multirescloth.simulate(skirt, {frames: frames, pins: "top", colliders: [sphere], output: withSphere});
expectEqual([report.frames, report.steps, report.nonFinite, report.cancelled], [frames, frames * 4, false, false],
            "run completed");
expectEqual([report.vertices, report.pinnedVertices, report.hangingVertices], [info.vertices, 40, 0],
            "the waist loop (40 vertices) is pinned");
if (!(report.maxPenetration <= 1e-4)) throw new Error("maxPenetration " + report.maxPenetration + " > 1e-4 m");
if (!(report.maxStretch < 0.1)) throw new Error("maxStretch " + report.maxStretch + " >= 0.1");
if (!(report.msPerFrame.collision > 0)) throw new Error("no time spent in collisions: " + JSON.stringify(report.msPerFrame));
expectEqual(core.fileSize(withSphere), 32 + frames * info.vertices * 12, "PC2 size");

const free = multirescloth.simulate(skirt, {frames: frames, pins: "top", output: without});
expectEqual([free.nonFinite, free.maxPenetration], [false, 0], "without the sphere");
if (core.filesEqual(withSphere, without)) throw new Error("the sphere did not change the motion");

print("simulate skirt: penetration " + report.maxPenetration + " m, stretch " + report.maxStretch.toFixed(4) +
      ", " + report.msPerFrame.total.toFixed(2) + " ms/frame: ok");
