// Cloth-cloth contact is for coarse garments for now: simulate warns before
// a run that asks for it on a mesh whose edges are, on average, shorter
// than twice its reach (thickness + gathering reach), and not otherwise.
// The embedded skirt (26 mm edges) runs quietly; refined once (13.2 mm) it
// is warned about (run_and_check: one warning, naming 13.2 mm).
"use strict";
const skirt = core.loadObject(core.resourcePath() + "/garments/default_skirt.obj");
const fine = multirescloth.refineUniform(skirt, 1);
for (const id of [skirt, fine]) {
  const report = multirescloth.simulate(id, {frames: 1, pins: "top", selfContact: 0.003});
  if (report.frames !== 1) throw new Error("object " + id + " simulated " + report.frames + " frames");
}
print("self-contact runs: 2");
