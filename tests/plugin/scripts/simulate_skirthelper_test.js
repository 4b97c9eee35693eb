// The shared MakeHuman skirt helper (decimetres), refined adaptively from
// painted modes (so it has T-nodes), pinned at its waist, hanging around a
// capsule standing in for the body. Skipped (exit 77) when ../shared/data is
// absent. Arguments: <tests/data> <shared data> <tmp>.
"use strict";
const [, sharedDir, tmpDir] = core.scriptArguments();
const path = sharedDir + "/garments/makehuman/skirthelper.obj";
core.include("test_asserts.js");
skipUnlessFiles([path]);

core.makePath(tmpDir);
const skirt = core.loadObject(path, {units: "dm"});
const box = core.objectInfo(skirt).bbox, height = box.max[1] - box.min[1];
const front = [0, box.min[1] + 0.25 * height, box.max[2]];
multirescloth.paintModes(skirt, {center: front, radius: 0.6 * height, mode: 2});
multirescloth.paintModes(skirt, {center: front, radius: 0.3 * height, mode: 3});
const multi = multirescloth.refineAdaptive(skirt, {delta: 8, maxLevel: 3, balance: true});
const info = core.objectInfo(multi);
if (!(info.hangingNodes > 0)) throw new Error("expected T-nodes, got " + info.hangingNodes);

// A vertical capsule through the middle of the skirt, narrowest (10.2 cm from
// the axis) just inside the cloth: legs and hips in one shape.
const cx = (box.min[0] + box.max[0]) / 2, cz = (box.min[2] + box.max[2]) / 2;
const body = {type: "capsule", a: [cx, box.min[1] + 0.3 * height, cz], b: [cx, box.max[1] - 0.1 * height, cz],
              radius: 0.095, thickness: 0.003, friction: 0.5};
const frames = 20, pc2 = tmpDir + "/skirthelper.pc2";
const report = multirescloth.simulate(multi, {frames: frames, pins: "top", colliders: [body], output: pc2});

expectEqual([report.frames, report.steps, report.nonFinite, report.cancelled], [frames, frames * 4, false, false],
            "run completed");
expectEqual([report.vertices, report.hangingVertices], [info.vertices, info.hangingNodes], "vertex classes");
expectEqual(report.freeVertices + report.pinnedVertices + report.hangingVertices, info.vertices, "classes add up");
if (!(report.pinnedVertices > 0)) throw new Error("nothing pinned");
if (!(report.maxPenetration <= 1e-4)) throw new Error("maxPenetration " + report.maxPenetration + " > 1e-4 m");
if (!(report.maxStretch < 0.1)) throw new Error("maxStretch " + report.maxStretch + " >= 0.1");
expectEqual(core.fileSize(pc2), 32 + frames * info.vertices * 12, "PC2 size");
const free = multirescloth.simulate(multi, {frames: frames, pins: "top", output: tmpDir + "/skirthelper_free.pc2"});
if (free.nonFinite || core.filesEqual(pc2, free.output)) throw new Error("the capsule did not change the motion");
print("simulate skirt helper: " + info.vertices + " vertices (" + info.hangingNodes + " T-nodes), " +
      report.msPerFrame.total.toFixed(1) + " ms/frame: ok");
