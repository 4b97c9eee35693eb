// A curvature picture of a mesh whose analysed cache never bent (a sheet
// held flat, no gravity) is one colour: render says why, and does not tell
// the user to run the extractModes they ran (run_and_check checks the
// warning). Argument: <tests/data>.
"use strict";
const [dataDir] = core.scriptArguments();
const grid = core.loadObject(dataDir + "/grid3x3.obj");
multirescloth.simulate(grid, {frames: 3, gravity: [0, 0, 0], output: "flat_curvature.pc2"});
multirescloth.extractModes(grid, "flat_curvature.pc2", {clusters: 1});
const largest = Math.max(...multirescloth.getLayer(grid, "mean_curvature"));
if (largest !== 0) throw new Error("the flat sheet's largest mean curvature is " + largest + ", not 0");
preview.render(grid, "flat_curvature.png", {colorBy: "curvature", width: 64, height: 64});
print("flat curvature rendered");
