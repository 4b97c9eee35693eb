// A garment with triangles loads as an all-quad mesh (each triangle split
// into 3 quads), with a [warn] line saying so (checked by run_and_check.cmake).
// The triangulated file is made by exporting the 3 x 3 grid with triangulate.
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
print("load warning: ok");
