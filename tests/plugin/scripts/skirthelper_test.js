// A real garment (MakeHuman skirt helper, decimetres) from the shared data;
// skipped (exit 77) when ../shared/data is absent.
"use strict";
const [, sharedDir] = core.scriptArguments();
const path = sharedDir + "/garments/makehuman/skirthelper.obj";
core.include("test_asserts.js");
skipUnlessFiles([path]);
function sum(list) { return list.reduce((a, b) => a + b, 0); }

const skirt = core.loadObject(path, {units: "dm"});
const coarse = core.objectInfo(skirt);
expectEqual([coarse.vertices, coarse.faces, coarse.hangingNodes], [720, 684, 0], "coarse skirt helper");
expectNearRelative(coarse.totalMass, 0.15 * coarse.area, 1e-12, "coarse mass = 0.15 * area");
// Decimetres became metres: the helper is about 0.6 m wide and 0.9 m tall.
expectNearRelative(coarse.bbox.max[0] - coarse.bbox.min[0], 0.6005, 1e-3, "width in metres");
expectNearRelative(coarse.bbox.max[1] - coarse.bbox.min[1], 0.91231, 1e-3, "height in metres");

const high = multirescloth.refineUniform(skirt, 2);
const fine = core.objectInfo(high);
expectEqual([fine.vertices, fine.faces, fine.hangingNodes], [11088, 10944, 0], "uniform x2");
expectEqual(fine.facesPerLevel, [0, 0, 0, 10944], "uniform x2 facesPerLevel");
expectNearRelative(fine.area, coarse.area, 1e-12, "area after uniform refinement");
expectNearRelative(fine.totalMass, 0.15 * fine.area, 1e-12, "fine mass = 0.15 * area");

// Paint the front of the lower half and refine adaptively.
const box = coarse.bbox, height = box.max[1] - box.min[1];
const center = [0, box.min[1] + 0.25 * height, box.max[2]];
const painted2 = multirescloth.paintModes(skirt, {center: center, radius: 0.6 * height, mode: 2});
const painted3 = multirescloth.paintModes(skirt, {center: center, radius: 0.3 * height, mode: 3});
if (!(painted2 > painted3 && painted3 > 0)) throw new Error("brushes painted " + painted2 + " and " + painted3);
const multi = multirescloth.refineAdaptive(skirt, {delta: 8, maxLevel: 3, balance: true});
const report = multirescloth.lastReport();
const info = core.objectInfo(multi);
expectEqual([report.vertices, report.faces, report.hangingNodes, report.facesPerLevel],
            [info.vertices, info.faces, info.hangingNodes, info.facesPerLevel], "report agrees with objectInfo");
if (!(info.hangingNodes > 0)) throw new Error("expected T-nodes, got " + info.hangingNodes);
if (!(info.vertices > coarse.vertices && info.vertices < fine.vertices))
  throw new Error("multi-resolution vertex count " + info.vertices + " not between coarse and fine");
expectEqual(sum(info.facesPerLevel), info.faces, "facesPerLevel sums to faces");
expectEqual(sum(info.verticesPerLevel), info.vertices, "verticesPerLevel sums to vertices");
expectEqual(info.maxLevel, 3, "maxLevel reached");
if (!(report.facesRefinedPerPass.length >= 1 && report.facesRefinedPerPass.every(count => count > 0)))
  throw new Error("facesRefinedPerPass " + JSON.stringify(report.facesRefinedPerPass));
expectNearRelative(info.totalMass, 0.15 * info.area, 1e-12, "multi-resolution mass = 0.15 * area");
expectNearRelative(info.area, coarse.area, 1e-12, "area after adaptive refinement");
print("skirt helper: " + info.vertices + " vertices, " + info.faces + " faces, " + info.hangingNodes +
      " hanging nodes, faces per level " + JSON.stringify(info.facesPerLevel) + ": ok");
