// Recording an instance motion (the paper's analysis input): the embedded
// default skirt worn by the embedded mannequin walking, its waist pinned to
// the pelvis, colliding with capsules along the bones. The result is a PC2
// point cache plus the rest mesh it plays on (same name, .obj).
//
// Usage: mrcloth -b record_example.js -- <output folder> [<frames>]
//   output folder  gets walk_instance.pc2 (the motion) and walk_instance.obj
//   frames         default 200 (6.7 s at 30 fps)
// Ctrl-C stops the recording (after the 1 s pre-roll); nothing is left behind.
//
// Playing it in Blender: import walk_instance.obj (File > Import > Wavefront;
// the cache needs its vertex order unchanged), add a Mesh Cache modifier,
// format PC2, file walk_instance.pc2, and set the modifier's axes to the
// ones the OBJ was imported with (both files are in metres, Y up, the
// character walking along +Z). To see the character, import
// resources/characters/walk_instance.bvh (scale 1: it is in metres). Timing:
// cache sample k is the character (k + 1) / fps seconds after the BVH's
// frame 1 (its frame 0 is the T-pose that skipFirst drops).
//
// The embedded files are in metres. CMU clips are not: pass
// {path: "07_06.bvh", units: "cmu"}. MakeHuman garments (base.obj, loaded
// with units "dm") go on the skinned MakeHuman body with
//   body: {type: "mesh", obj: ".../base.obj", skeleton: ".../cmu_mb.mhskel",
//          weights: ".../default_weights.mhw"}, place: "makehuman".
// Every option is listed by: mrcloth --api
"use strict";

const args = core.scriptArguments();
const outDir = args[0];
const frames = args[1] === undefined ? 200 : Number(args[1]);
if (outDir === undefined) {
  print("usage: mrcloth -b record_example.js -- <output folder> [<frames>]");
  core.exitApplication(2);
}

const skirt = core.loadObject(core.resourcePath() + "/garments/default_skirt.obj");
const info = core.objectInfo(skirt);
print("loaded " + info.name + ": " + info.vertices + " vertices, " + info.faces + " quads");
const walk = core.resourcePath() + "/characters/walk_instance.bvh";

core.makePath(outDir);
const report = multirescloth.recordInstance(skirt, {
  motion: {path: walk, units: "m", skipFirst: true},  // metres; drop the T-pose of frame 0
  body: "capsules",           // a tapered capsule per bone, sized for the skeleton
  place: "firstFrame",        // the skirt was modelled on the mannequin's T-pose (frame 0)
  waist: "top",               // the highest boundary loop follows the pelvis
  preroll: 1.0,               // 1 s from the T-pose into the first frame, not recorded
  frames: frames,
  fps: 30,
  stepRate: 120,              // implicit steps per second
  output: outDir + "/walk_instance.pc2",
});
print("recorded " + report.frames + " frames of " + report.motion.split("/").pop() + " (" + report.body + ", " +
      report.capsules + " capsules) after a " + report.preroll.seconds + " s pre-roll: " +
      report.msPerFrame.total.toFixed(1) + " ms per frame (dynamics " + report.msPerFrame.dynamics.toFixed(1) +
      ", collisions " + report.msPerFrame.collision.toFixed(1) + ")");
print("  max stretch " + (100 * report.maxStretch).toFixed(2) + " %, max penetration " +
      (1000 * report.maxPenetration).toFixed(3) + " mm, waist error " + report.maxWaistError.toExponential(1) + " m" +
      (report.nonFinite ? ", NOT FINITE" : ""));
if (report.output !== "") print("  cache: " + report.output + "\n  rest mesh: " + report.restMesh);

// Mistakes are exceptions that name the option and list what is accepted.
try {
  multirescloth.recordInstance(skirt, {motion: {path: walk, units: "feet"}, output: outDir + "/never.pc2"});
} catch (error) {
  print("as expected: " + error.name + ": " + error.message);
}
