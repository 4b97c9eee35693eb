// simulate's limiterAcceleration: a number fixes the limiter's Chebyshev
// estimate; "auto", the default, raises 0.97 to cos^2(pi / (n + 1)) for the garment's
// longest chain of n stretch springs from a pin: the embedded skirt, 20
// rings pinned at the top, has 19; refined once, 38 (each ring and the
// rows between them split). The report says which estimate was used.
"use strict";
core.include("test_asserts.js");
const skirt = core.loadObject(core.resourcePath() + "/garments/default_skirt.obj");
const once = multirescloth.refineUniform(skirt, 1);
const used = (id, acceleration) => {
  const options = {frames: 1, pins: "top"};
  if (acceleration !== undefined) options.limiterAcceleration = acceleration;
  return multirescloth.simulate(id, options).limiterAcceleration;
};
const chain = (links) => Math.pow(Math.cos(Math.PI / (links + 1)), 2);
if (!(Math.abs(used(once) - chain(38)) < 1e-15)) throw new Error("the default refined once: " + used(once));
expectEqual(used(skirt, 0.97), 0.97, "a number");
expectEqual(used(once, 0.5), 0.5, "a number is kept on a longer chain");
if (!(Math.abs(used(skirt, "auto") - chain(19)) < 1e-15)) throw new Error("auto on the skirt: " + used(skirt, "auto"));
if (!(Math.abs(used(once, "auto") - chain(38)) < 1e-15)) throw new Error("auto refined once: " + used(once, "auto"));
expectEqual(used(skirt, 0), 0, "plain sweeps stay plain");
expectThrows(() => used(skirt, "fast"), "ArgumentError",
             "option 'limiterAcceleration' must be \"auto\" or a number >= 0 and < 1 (0: plain limiter sweeps), got the string \"fast\"");
print("limiter acceleration: ok");
