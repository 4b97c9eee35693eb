// A job whose first progress state comes after a long set-up: the embedded
// skirt on the embedded mannequin with a 2 s pre-roll (240 steps) before
// the first of 4 frames. Until a second state the host knows no rate, so
// its first line carries none (it once printed a rate and ETA measured
// from the start, the pre-roll included). Used by the progress checks.
"use strict";
const walk = core.resourcePath() + "/characters/walk_instance.bvh";
const skirt = core.loadObject(core.resourcePath() + "/garments/default_skirt.obj");
const report = multirescloth.simulate(skirt, {
  motion: {path: walk, units: "m"}, body: {type: "capsules"}, place: "firstFrame", preroll: 2.0, frames: 4});
print("frames " + report.frames);
