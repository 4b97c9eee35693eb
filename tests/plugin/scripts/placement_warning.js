// A garment whose waist starts far from the pelvis gets a warning before
// the run, kept in the report; its advice depends on the placement. With
// place "makehuman" the garment is already where its file puts it against
// the body file's, so the files disagree (a sweep: a base.obj moved by 0.9 m
// was told to set the place it had). The shared skirt moved 0.5 m along x,
// on capsules fitted to the MakeHuman body, one frame. Skipped (exit 77)
// without ../shared/data. Arguments: <tests/data> <shared data> <tmp>.
"use strict";
const [, sharedDir, tmpDir] = core.scriptArguments();
core.include("test_asserts.js");
const {garment, clip, body} = sharedMakeHuman(sharedDir, "skirthelper.obj", "capsules");
core.makePath(tmpDir);
const moved = tmpDir + "/skirt_moved.obj";
core.writeTextFile(moved, core.readTextFile(garment).split("\n").map((line) => {
  if (!line.startsWith("v ")) return line;
  const [x, y, z] = line.slice(2).trim().split(/\s+/).map(Number);
  return "v " + (x + 5) + " " + y + " " + z;  // decimetres
}).join("\n"));
const run = (file, place) => multirescloth.simulate(core.loadObject(file, {units: "dm"}), {
  motion: {path: clip, units: "cmu"}, body: body, place: place, preroll: 0, frames: 1, fitWarning: false}).warnings;
const far = (warnings) => warnings.filter((w) => w.includes("the pinned waist is"));
expectEqual(far(run(garment, "makehuman")), [], "the shared skirt where it belongs");
const filesDisagree = far(run(moved, "makehuman"));
expectEqual(filesDisagree.length, 1, "the moved skirt: " + JSON.stringify(filesDisagree));
expectEqual([filesDisagree[0].includes("the garment's file and the body's do not share their coordinates"),
             filesDisagree[0].includes("option 'place': \"makehuman\" for")], [true, false], filesDisagree[0]);
const unplaced = far(run(garment, "none"));
expectEqual(unplaced.length, 1, "the skirt left in MakeHuman's coordinates: " + JSON.stringify(unplaced));
expectEqual(unplaced[0].includes("the garment is probably not placed on the character (option 'place': \"makehuman\" for"),
            true, unplaced[0]);
print("placement warnings: ok");
