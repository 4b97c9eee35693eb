// A pre-roll too short for the legs' way from the rest pose to the
// motion's first frame (preroll_leg_speed above 8 m/s) is warned of before
// the run, with the pre-roll that would do (run_and_check); the default
// skirt on the new walk: none at 0.5 s, at 0.02 s 23 m/s, at 0 in one step.
"use strict";
const skirt = core.loadObject(core.resourcePath() + "/garments/default_skirt.obj");
for (const preroll of [0.5, 0.02, 0])
  multirescloth.simulate(skirt, {motion: {path: core.resourcePath() + "/characters/walk_new.bvh"}, body: "capsules",
                                 place: "firstFrame", preroll: preroll, frames: 1, fitWarning: false});
print("pre-roll warnings: ok");
