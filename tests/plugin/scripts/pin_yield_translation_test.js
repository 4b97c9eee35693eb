// The embedded skirt pinned at its waist, with a sphere overlapping the
// front of the waist by about 5 mm, and the same scene moved across the
// floor: the pins inside yield onto the sphere, the same distance in every
// placement. The surface point measured a round-off's depth in some
// placements and the pin went out to the thickness instead (2 mm farther;
// the metamorphic sweep, 2026-11-28).
"use strict";
core.include("test_asserts.js");
const out = core.scriptArguments()[2];
core.makePath(out);
const skirtText = core.readTextFile(core.resourcePath() + "/garments/default_skirt.obj");

/// The skirt moved by (dx, 0, dz), as an OBJ file in the test's folder.
function movedSkirt(dx, dz) {
  const lines = skirtText.split("\n").map((line) => {
    if (!line.startsWith("v ")) return line;
    const [, x, y, z] = line.trim().split(/\s+/).map(Number);
    return "v " + (x + dx) + " " + y + " " + (z + dz);
  });
  const path = out + "/skirt_" + dx + "_" + dz + ".obj";
  core.writeTextFile(path, lines.join("\n"));
  return core.loadObject(path);
}

const yields = [];
for (const [dx, dz] of [[0, 0], [0.3, -0.7], [0.37, 0.51], [3, -2], [-1.1, 0.9]]) {
  const report = multirescloth.simulate(movedSkirt(dx, dz), {
    frames: 2, pins: "top",
    colliders: [{type: "sphere", center: [dx, 1.02, 0.17 + dz], radius: 0.083, thickness: 0.002}]});
  print("moved by (" + dx + ", 0, " + dz + "): maxPinYield " + (1000 * report.maxPinYield).toFixed(6) + " mm");
  yields.push(report.maxPinYield);
}
expectAtLeast(yields[0], 0.004, "the pins inside the sphere yield");
for (const y of yields) expectNear(y, yields[0], 1e-6, "the yield wherever the scene stands");
