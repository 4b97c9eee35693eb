// A short tour of the scripting API: load a garment, look at it, paint modes
// two ways, and refine it adaptively with two thresholds (as the paper shows
// two skirts from one set of modes). Writes nothing unless given a folder.
//
// Usage: mrcloth -b example_refine.js [-- <output folder>]
// Every call is listed by: mrcloth --api
"use strict";

const outDir = core.scriptArguments()[0];  // undefined: write nothing

// Objects are integer ids; the meshes stay in the host.
const skirt = core.loadObject(core.resourcePath() + "/garments/default_skirt.obj");
const info = core.objectInfo(skirt);
print("loaded " + info.name + ": " + info.vertices + " vertices, " + info.faces + " quads, " +
      info.area.toFixed(3) + " m^2, " + (1000 * info.totalMass).toFixed(1) + " g");

// Modes: 1 (the default) = little deformation, higher = more. Set them on a
// list of vertex ids (here: reset every vertex to 1)...
const everyVertex = [];
for (let vertex = 0; vertex < info.vertices; ++vertex) everyVertex.push(vertex);
multirescloth.setModes(skirt, everyVertex, 1);
// ...or with a sphere brush (centre and radius in metres).
const box = info.bbox;
const painted = multirescloth.paintModes(skirt, {
  center: [0, box.min[1], box.max[2]],  // front of the hem
  radius: 0.5 * (box.max[1] - box.min[1]),
  mode: 3,
});
print("painted " + painted + " vertices with mode 3");

// Refinement never changes its input: each call returns a new object.
for (const delta of [8, 10]) {
  const refined = multirescloth.refineAdaptive(skirt, {delta: delta, maxLevel: 3});
  const report = multirescloth.lastReport();
  print("delta " + delta + ": " + report.vertices + " vertices, " + report.faces + " faces, " +
        report.hangingNodes + " hanging nodes, faces per level " + report.facesPerLevel.slice(1).join("/") +
        ", " + report.milliseconds.toFixed(1) + " ms");
  if (outDir !== undefined) {
    core.makePath(outDir);
    multirescloth.exportSurface(refined, outDir + "/skirt_delta" + delta + ".ply", {colorBy: "level"});
  }
}

// Every failure is a JavaScript exception that names the call and the problem.
try {
  multirescloth.refineAdaptive(skirt, {detla: 8});
} catch (error) {
  print("as expected: " + error.name + ": " + error.message);
}
