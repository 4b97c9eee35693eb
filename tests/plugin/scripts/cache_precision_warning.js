// A PC2 cache keeps float32 positions: simulate warns when the garment lies
// so far from the origin that the file's steps pass 0.1 mm (beyond about
// 839 m), and only when it writes a cache. The same 40 cm sheet at 800 m
// (0.095 mm steps) and at 2000 m (0.24 mm); run_and_check: one warning,
// naming 2000 m.
"use strict";
function sheetAt(offset, file) {
  const lines = [];
  for (let j = 0; j <= 4; ++j)
    for (let i = 0; i <= 4; ++i) lines.push("v " + (offset + 0.1 * i) + " " + (1 + 0.1 * j) + " 0");
  for (let j = 0; j < 4; ++j)
    for (let i = 0; i < 4; ++i) {
      const a = 1 + j * 5 + i;
      lines.push("f " + a + " " + (a + 1) + " " + (a + 6) + " " + (a + 5));
    }
  core.writeTextFile(file, lines.join("\n") + "\n");
  return core.loadObject(file);
}
const near = sheetAt(800, "precision_near.obj"), far = sheetAt(2000, "precision_far.obj");
let runs = 0;
for (const [id, output] of [[near, "precision_near_run.pc2"], [far, "precision_far_run.pc2"], [far, undefined]]) {
  const options = {frames: 1, pins: "top"};
  if (output) options.output = output;
  const report = multirescloth.simulate(id, options);
  if (report.frames !== 1) throw new Error("object " + id + " simulated " + report.frames + " frames");
  ++runs;
}
print("precision runs: " + runs);
