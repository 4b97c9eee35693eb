// A job long enough for progress updates (about a second): the grid refined
// three times, hanging from its top row. Used by the progress-output checks.
"use strict";
const [dataDir] = core.scriptArguments();
const grid = multirescloth.refineUniform(core.loadObject(dataDir + "/grid3x3.obj"), 3);
const report = multirescloth.simulate(grid, {frames: 3000, pins: "top"});
print("frames " + report.frames);
