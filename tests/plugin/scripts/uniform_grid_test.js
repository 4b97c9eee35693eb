// refineUniform on the 3 x 3 unit grid: exact counts, the input untouched,
// fresh ids, and mass = density * area. Arguments: <tests/data> <shared data> <tmp>.
"use strict";
const [dataDir] = core.scriptArguments();

core.include("test_asserts.js");

const grid = core.loadObject(dataDir + "/grid3x3.obj");
expectEqual(grid, 1, "first object id");
const coarse = core.objectInfo(grid);
expectEqual([coarse.vertices, coarse.faces, coarse.hangingNodes, coarse.maxLevel, coarse.boundaryLoops], [16, 9, 0, 1, 1],
            "coarse grid");
expectEqual(coarse.facesPerLevel, [0, 9], "coarse facesPerLevel");
expectEqual(coarse.verticesPerLevel, [0, 16], "coarse verticesPerLevel");
expectEqual(coarse.verticesPerMode, [0, 16], "every vertex starts in mode 1");
expectEqual(coarse.bbox, {max: [3, 3, 0], min: [0, 0, 0]}, "bbox");
expectNearRelative(coarse.area, 9, 1e-12, "area of the 3 x 3 grid (m^2)");
expectNearRelative(coarse.totalMass, 0.15 * 9, 1e-12, "mass of the 3 x 3 grid (kg)");

// Each refinement is a new object; the input keeps its 16 vertices.
const once = multirescloth.refineUniform(grid, 1);
const twice = multirescloth.refineUniform(grid, 2);
expectEqual([once, twice], [2, 3], "ids of the refined copies");
const info1 = core.objectInfo(once), info2 = core.objectInfo(twice);
expectEqual([info1.vertices, info1.faces, info1.hangingNodes, info1.maxLevel], [49, 36, 0, 2], "refined once");
expectEqual(info1.facesPerLevel, [0, 0, 36], "refined once: facesPerLevel");
expectEqual([info2.vertices, info2.faces, info2.hangingNodes, info2.maxLevel], [169, 144, 0, 3], "refined twice");
expectEqual(info2.facesPerLevel, [0, 0, 0, 144], "refined twice: facesPerLevel");
expectEqual(info2.verticesPerLevel.reduce((a, b) => a + b, 0), 169, "verticesPerLevel sums to the vertices");
expectEqual(core.objectInfo(grid).vertices, 16, "input untouched");

// The report describes the last refinement.
const report = multirescloth.lastReport();
expectEqual([report.operation, report.source, report.result, report.levels], ["refineUniform", 1, 3, 2], "report");
expectEqual([report.vertices, report.faces, report.hangingNodes], [169, 144, 0], "report counts");
expectEqual(report.facesPerLevel, info2.facesPerLevel, "report facesPerLevel");
if (!(report.milliseconds >= 0)) throw new Error("report milliseconds: " + report.milliseconds);

// Refinement keeps the area and so the mass (to rounding).
for (const info of [info1, info2]) {
  expectNearRelative(info.area, coarse.area, 1e-12, "area after refinement");
  expectNearRelative(info.totalMass, 0.15 * info.area, 1e-12, "mass = 0.15 kg/m^2 * area");
}

// Refining an already refined copy composes: (grid x1) x1 == grid x2.
const composed = core.objectInfo(multirescloth.refineUniform(once, 1));
expectEqual([composed.vertices, composed.faces, composed.facesPerLevel], [169, 144, [0, 0, 0, 144]], "x1 then x1");

// Zero levels is a plain copy.
const copy = core.objectInfo(multirescloth.refineUniform(grid, 0));
expectEqual([copy.vertices, copy.faces], [16, 9], "zero levels");

expectEqual(core.objectList().map(object => object.id), [1, 2, 3, 4, 5], "objectList ids");
core.deleteObject(5);
expectEqual(core.objectList().map(object => object.id), [1, 2, 3, 4], "after deleteObject");
expectEqual(core.loadObject(dataDir + "/grid3x3.obj"), 6, "ids are never reused");
print("uniform grid: ok");
