// selfContact {thickness, neighbourhood} reaches the solver: accordion
// pleats whose faces lie 2.9 mm apart, joined 13 mm along the sheet, are
// pushed apart by a 3 mm contact without a neighbourhood (their springs
// stretch within one frame) and left alone by the default one (26 mm: one
// sheet, nothing moves without gravity). Arguments: <tests/data> <shared data> <tmp>.
"use strict";
const [, , tmpDir] = core.scriptArguments();
core.include("test_asserts.js");
core.makePath(tmpDir);
// Pleats 1.5 mm apart along x, 6 mm deep, a strip 1 cm wide (z), 3 vertices across.
const lines = [];
for (let i = 0; i < 10; ++i)
  for (let j = 0; j < 3; ++j) lines.push("v " + 0.0015 * i + " " + 0.006 * (i % 2) + " " + 0.005 * j);
const id = (i, j) => i * 3 + j + 1;
for (let i = 0; i < 9; ++i)
  for (let j = 0; j < 2; ++j) lines.push("f " + [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)].join(" "));
core.writeTextFile(tmpDir + "/pleats.obj", lines.join("\n") + "\n");
const pleats = core.loadObject(tmpDir + "/pleats.obj");
const stretch = (selfContact) =>
  multirescloth.simulate(pleats, {frames: 1, gravity: [0, 0, 0], pins: [0, 1, 2], selfContact: selfContact}).maxStretch;
expectEqual(stretch({thickness: 0.003}), 0, "default neighbourhood: the pleats are one sheet, nothing moves");
expectEqual(stretch(0.003), 0, "a thickness alone takes the default neighbourhood");
if (!(stretch({thickness: 0.003, neighbourhood: 0}) > 0.001))
  throw new Error("without a neighbourhood the pleats should push each other apart and stretch");
print("self-contact neighbourhood: ok");
