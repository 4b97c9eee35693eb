// A garment with triangles loads as an all-quad mesh (each triangle split
// into 3 quads), with a [warn] line saying so (checked by run_and_check.cmake).
// The triangulated file is made by exporting the 3 x 3 grid with triangulate.
// And loadModes warns when a CSV sets only some of a mesh's vertices, or
// its positions do not fit the mesh's.
"use strict";
const [dataDir, , tmpDir] = core.scriptArguments();
core.makePath(tmpDir);
const grid = core.loadObject(dataDir + "/grid3x3.obj");
multirescloth.exportSurface(grid, tmpDir + "/triangulated.obj", {triangulate: true});

const info = core.objectInfo(core.loadObject(tmpDir + "/triangulated.obj"));
// 18 triangles -> 54 quads; vertices: 16 corners + 18 centres + 33 edge midpoints.
if (info.faces !== 54 || info.vertices !== 67)
  throw new Error("triangulated grid: expected 67 vertices and 54 faces, got " + info.vertices + " and " + info.faces);
if (Math.abs(info.area - 9) > 1e-12 * 9) throw new Error("area " + info.area);
// The coarse grid's modes loaded into its refinement set 16 of its 49
// vertices: legitimate for a tool's selection, but warned of.
multirescloth.saveLayers(grid, tmpDir + "/coarse_layers.csv");
const refined = multirescloth.refineUniform(grid, 1);
if (multirescloth.loadModes(refined, tmpDir + "/coarse_layers.csv") !== 16) throw new Error("rows read");
if (multirescloth.loadModes(grid, tmpDir + "/coarse_layers.csv") !== 16) throw new Error("rows read, whole");
// The same CSV into the grid read in decimetres: as many vertices, but every
// row's position save the origin's lies elsewhere (the far corner 3.82 m off).
const small = core.loadObject(dataDir + "/grid3x3.obj", {units: "dm"});
if (multirescloth.loadModes(small, tmpDir + "/coarse_layers.csv") !== 16) throw new Error("rows read, scaled");
print("load warning: ok");
