// .om keeps the hierarchy and every layer; OBJ/PLY exports keep the active surface.
"use strict";
const [dataDir, , tmpDir] = core.scriptArguments();

core.include("test_asserts.js");
function summary(id) {
  const info = core.objectInfo(id);
  return [info.vertices, info.faces, info.hangingNodes, info.facesPerLevel, info.verticesPerLevel,
          info.verticesPerMode, info.bbox];
}

core.makePath(tmpDir + "/nested/folder");
if (!core.fileExists(tmpDir + "/nested/folder")) throw new Error("makePath did not create the folder");
core.makePath(tmpDir + "/nested/folder");  // existing: no error

const grid = core.loadObject(dataDir + "/grid3x3.obj");
multirescloth.setModes(grid, [5, 6, 9, 10], 3);
const refined = multirescloth.refineAdaptive(grid, {delta: 8, maxLevel: 3});

// Round trip through .om: the same mesh, hierarchy and layers; and it can be refined further.
const omPath = tmpDir + "/refined.om";
core.saveObject(refined, omPath);
expectEqual(core.objectInfo(refined).path, omPath, "saveObject records the path");
const reloaded = core.loadObject(omPath);
expectEqual(summary(reloaded), summary(refined), "after .om round trip");
expectEqual(multirescloth.getModes(reloaded), multirescloth.getModes(refined), "modes after .om round trip");
const further = core.objectInfo(multirescloth.refineUniform(reloaded, 1));
expectEqual(further.maxLevel, 4, "a reloaded hierarchy refines on");

// Exports of every kind.
for (const [file, options] of [["surface.obj", {}],
                               ["by_level.ply", {colorBy: "level"}],
                               ["by_mode.ply", {colorBy: "mode", triangulate: true}],
                               ["plain.ply", {colorBy: "none", triangulate: false}]]) {
  multirescloth.exportSurface(refined, tmpDir + "/" + file, options);
  if (!core.fileExists(tmpDir + "/" + file)) throw new Error("export did not write " + file);
}

// An OBJ export of a conforming mesh (no T-nodes, all quads) reads back as the same surface.
const uniform = multirescloth.refineUniform(grid, 1);
multirescloth.exportSurface(uniform, tmpDir + "/uniform.obj");
const surface = core.objectInfo(core.loadObject(tmpDir + "/uniform.obj"));
expectEqual([surface.vertices, surface.faces, surface.bbox], [49, 36, core.objectInfo(uniform).bbox],
            "OBJ export read back");
print("save/load: ok");
