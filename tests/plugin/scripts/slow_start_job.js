// A job whose first progress state comes after a long set-up: the grid
// refined five times (9,409 vertices), whose factorisation comes before
// its first frame. Until a second state the host knows no rate, so the
// first line carries none (it once printed a rate and an ETA measured from
// the start, the set-up included). Used by the progress checks.
"use strict";
const [dataDir] = core.scriptArguments();
const grid = multirescloth.refineUniform(core.loadObject(dataDir + "/grid3x3.obj"), 5);
const report = multirescloth.simulate(grid, {frames: 3, pins: "top"});
print("frames " + report.frames);
