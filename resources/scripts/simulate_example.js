// Simulating a garment: refine the embedded skirt adaptively, hang it from
// its waist around a simple body (a tapered capsule for hips and legs, a
// sphere for a knee stepping forward, a floor), and record the motion as a
// PC2 point cache that Blender's Mesh Cache modifier, Maya or Marvelous
// Designer can play on the refined mesh.
//
// Usage: mrcloth -b simulate_example.js [-- <output folder> [<frames>]]
//   output folder  gets skirt.om (the refined mesh), skirt.pc2 (its motion)
//                  and skirt_last_frame.obj; nothing is written without it
//   frames         default 60 (2 s at 30 fps)
// Ctrl-C stops the simulation; no partial cache is left behind.
// Every option of simulate is listed by: mrcloth --api
"use strict";

const args = core.scriptArguments();
const outDir = args[0];  // undefined: write nothing
const frames = args[1] === undefined ? 60 : Number(args[1]);

// The mesh: the coarse skirt, refined where a painted mode layer asks for it
// (the front of the hem, where a stride wrinkles it), as in example_refine.js.
const skirt = core.loadObject(core.resourcePath() + "/garments/default_skirt.obj");
const info = core.objectInfo(skirt);
print("loaded " + info.name + ": " + info.vertices + " vertices, " + info.faces + " quads");
const box = info.bbox;
multirescloth.paintModes(skirt, {center: [0, box.min[1], box.max[2]], radius: 0.5 * (box.max[1] - box.min[1]), mode: 3});
const refined = multirescloth.refineAdaptive(skirt, {delta: 8, maxLevel: 3});
const refinedInfo = core.objectInfo(refined);
print("refined: " + refinedInfo.vertices + " vertices, " + refinedInfo.hangingNodes + " hanging nodes");

// Everything is in metres and seconds; y is up, the skirt faces +z.
const options = {
  frames: frames,
  fps: 30,
  substeps: 4,                 // 4 implicit steps per frame (h = 1/120 s)
  material: {preset: "cotton", damping: 0.3},
  pins: "top",                 // the waist: the highest boundary loop
  colliders: [
    {type: "capsule", a: [0, 0.55, 0], b: [0, 0.95, 0], radiusA: 0.10, radiusB: 0.115, friction: 0.4},
    {type: "sphere", center: [0, 0.62, 0.06], radius: 0.1},   // a knee pushing the front out
    {type: "plane", point: [0, 0, 0], normal: [0, 1, 0]},       // the floor
  ],
  updateObject: outDir !== undefined,  // keep the last frame as a new object
};
if (outDir !== undefined) {
  core.makePath(outDir);
  core.saveObject(refined, outDir + "/skirt.om");  // the mesh the cache plays on
  options.output = outDir + "/skirt.pc2";
}

const report = multirescloth.simulate(refined, options);
print("simulated " + report.frames + " frames (" + report.steps + " steps of " + (1000 * report.timeStep).toFixed(2) +
      " ms): " + report.msPerFrame.total.toFixed(1) + " ms per frame (dynamics " +
      report.msPerFrame.dynamics.toFixed(1) + ", collisions " + report.msPerFrame.collision.toFixed(1) +
      "), set-up " + report.precomputeMs.toFixed(1) + " ms");
print("  " + report.freeVertices + " free, " + report.pinnedVertices + " pinned, " + report.hangingVertices +
      " hanging vertices; springs: " + report.springs.stretch + " stretch, " + report.springs.shear + " shear, " +
      report.springs.bend + " bend");
print("  max stretch " + (100 * report.maxStretch).toFixed(2) + " %, max penetration " +
      (1000 * report.maxPenetration).toFixed(3) + " mm" + (report.nonFinite ? ", NOT FINITE" : ""));
if (report.output !== "") print("  cache: " + report.output);
if (report.resultId !== undefined) {
  core.saveObject(report.resultId, outDir + "/skirt_last_frame.obj");
  print("  last frame: " + outDir + "/skirt_last_frame.obj");
}

// Mistakes are exceptions that name the option and list what is accepted.
try {
  multirescloth.simulate(refined, {frames: 10, pin: "top"});
} catch (error) {
  print("as expected: " + error.name + ": " + error.message);
}
