// Cloth-cloth contact is for garments refined at most once for now:
// simulate warns before a run that asks for it on a mesh whose edges are,
// on average, shorter than its reach (thickness + gathering reach), and
// not otherwise. The embedded skirt (26 mm edges) and the skirt refined
// once (13.2 mm, just above the 13 mm reach) run quietly; refined twice
// (6.6 mm) it is warned about (run_and_check: one warning, naming 6.6 mm).
"use strict";
const skirt = core.loadObject(core.resourcePath() + "/garments/default_skirt.obj");
const once = multirescloth.refineUniform(skirt, 1);
const twice = multirescloth.refineUniform(skirt, 2);
for (const id of [skirt, once, twice]) {
  const report = multirescloth.simulate(id, {frames: 1, pins: "top", selfContact: 0.003});
  if (report.frames !== 1) throw new Error("object " + id + " simulated " + report.frames + " frames");
}
print("self-contact runs: 3");
