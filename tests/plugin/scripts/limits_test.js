// multirescloth.limits(): every bound it lists is the one the calls check,
// just beyond it refused with the range in the message, so a tool that
// checks its inputs against limits() (the pipeline does) agrees with the
// calls. Arguments: <tests/data> <shared data> <tmp>.
"use strict";
const [dataDir, , tmp] = core.scriptArguments();

core.include("test_asserts.js");

const L = multirescloth.limits();
expectEqual(Object.keys(L).sort().join(","),
            "clusters,collisionRounds,contactThickness,fps,garmentSpan,iterations,limiterSweeps,mode,motionSmoothing," +
            "newtonCg,preroll,refinedFaces,restarts,selfContactThickness,stepsPerFrame,substeps,threads", "the bounds listed");
for (const [name, range] of Object.entries(L)) {
  expectType(range, "array", name);
  expectEqual(range.length, 2, name + ": [least, most]");
  expectEqual(range.every(isFinite), true, name + " finite");
  expectAtLeast(range[1] - range[0], Number.MIN_VALUE, name + ": most - least");
}
const span = (name) => L[name][0] + " to " + L[name][1];

const grid = core.loadObject(dataDir + "/grid3x3.obj");
const sim = (options) => () => multirescloth.simulate(grid, options);
for (const name of ["substeps", "iterations", "newtonCg", "limiterSweeps", "collisionRounds", "threads"]) {
  for (const beyond of [L[name][0] - 1, L[name][1] + 1])
    expectThrows(sim({[name]: beyond}), "ArgumentError",
                 "option '" + name + "' must be an integer from " + span(name) + ", got the number " + beyond);
}
expectThrows(sim({fps: 2 * L.fps[1]}), "ArgumentError", "option 'fps' must be from " + span("fps") + " frames per second");
expectThrows(sim({fps: L.fps[0] / 2}), "ArgumentError", "option 'fps' must be from " + span("fps") + " frames per second");
expectThrows(sim({selfContact: 1.5 * L.selfContactThickness[1]}), "ArgumentError",
             "option 'selfContact' must be false or a thickness from " + span("selfContactThickness") + " m");
expectThrows(sim({colliders: [{type: "plane", thickness: 1.5 * L.contactThickness[1]}]}), "ArgumentError",
             "option 'colliders[0].thickness' must be from " + span("contactThickness") + " m");

// On a character.
const walk = core.resourcePath() + "/characters/walk_instance.bvh";
expectThrows(sim({motion: walk, body: {thickness: 1.5 * L.contactThickness[1]}}), "ArgumentError",
             "option 'body.thickness' must be from " + span("contactThickness") + " m");
for (const preroll of [L.preroll[0] / 2, L.preroll[1] + 1])
  expectThrows(sim({motion: walk, preroll: preroll}), "ArgumentError",
               "option 'preroll' must be 0 or a number of seconds from " + span("preroll") + ", got " + preroll);
expectThrows(sim({motion: walk, fps: 30, stepRate: 30 * L.stepsPerFrame[1] + 1}), "ArgumentError",
             "option 'stepRate' must be at most " + L.stepsPerFrame[1] + " steps per output frame");
expectThrows(sim({motion: {path: walk, smoothing: 2 * L.motionSmoothing[1]}}), "ArgumentError",
             "option 'motion.smoothing' must be at most " + L.motionSmoothing[1] + " s");
const tiny = core.loadObject(dataDir + "/grid3x3.obj", {units: "cm"});  // 3 cm across
expectThrows(() => multirescloth.simulate(tiny, {motion: walk}), "InputError",
             "expected " + L.garmentSpan[0] + "-" + L.garmentSpan[1] + " m for a garment worn by a person");

// Modes and refinement.
expectThrows(() => multirescloth.setModes(grid, [0], L.mode[1] + 1), "ArgumentError",
             "mode must be an integer from " + span("mode") + ", got the number " + (L.mode[1] + 1));
expectThrows(() => multirescloth.refineUniform(grid, 20), "ArgumentError",
             "would make more than " + L.refinedFaces[1] + " faces from 9");
expectEqual(multirescloth.setModes(grid, [0], L.mode[1]), 1, "the largest mode is accepted");
for (const name of ["clusters", "restarts"])
  for (const beyond of [L[name][0] - 1, L[name][1] + 1])
    expectThrows(() => multirescloth.extractModes(grid, "no_such.pc2", {[name]: beyond}), "ArgumentError",
                 "option '" + name + "' must be an integer from " + span(name) + ", got the number " + beyond);

// The previews' bounds (preview.limits()), which the pipeline checks --size against.
const P = preview.limits();
expectEqual(Object.keys(P).sort().join(","), "chartSide,imageSide,samples,sheetSide,supersample", "the previews' bounds listed");
const previewSpan = (name) => P[name][0] + " to " + P[name][1];
const image = tmp + "/limits.png";
for (const side of ["width", "height"]) {
  for (const beyond of [P.imageSide[0] - 1, P.imageSide[1] + 1])
    expectThrows(() => preview.render(grid, image, {[side]: beyond}), "ArgumentError",
                 "option '" + side + "' must be an integer from " + previewSpan("imageSide") + ", got the number " + beyond);
  const chart = {series: [{name: "a", y: [1, 2]}], [side]: P.chartSide[0] - 1};
  expectThrows(() => preview.lineChart(image, chart), "ArgumentError",
               "option '" + side + "' must be an integer from " + previewSpan("chartSide"));
  chart[side] = P.chartSide[1] + 1;
  expectThrows(() => preview.lineChart(image, chart), "ArgumentError",
               "option '" + side + "' must be an integer from " + previewSpan("chartSide"));
}
for (const beyond of [P.supersample[0] - 1, P.supersample[1] + 1])
  expectThrows(() => preview.render(grid, image, {supersample: beyond}), "ArgumentError",
               "option 'supersample' must be an integer from " + previewSpan("supersample") + ", got the number " + beyond);
// The largest square image at the largest supersample within the samples' bound, and one pixel row more.
const side = Math.floor(Math.sqrt(P.samples[1]) / P.supersample[1]);
expectThrows(() => preview.render(grid, image, {width: side, height: side + 1, supersample: P.supersample[1]}),
             "ArgumentError", "expected at most " + P.samples[1]);
expectEqual(core.fileExists(image), false, "nothing written by the refused renders");

// The largest chart (256 MB of pixels: over Qt's default 128 MB reader
// limit) goes into a contact sheet; two side by side would pass the sheet's bound
// (10 pixels of spacing around each cell, 22 below it for its caption).
core.makePath(tmp);
const tall = tmp + "/limits_tall.png", wide = tmp + "/limits_wide.png", sheet = tmp + "/limits_sheet.png";
preview.lineChart(tall, {series: [{name: "a", y: [1, 2]}], width: P.chartSide[1], height: P.chartSide[1]});
const one = preview.contactSheet([tall], sheet);
expectEqual(one.width, P.chartSide[1] + 20, "the sheet of the largest chart: its width (10 pixels each side)");
preview.lineChart(wide, {series: [{name: "a", y: [1, 2]}], width: P.chartSide[1], height: P.chartSide[0]});
core.removeFile(sheet);
const beyondSheet = 3 * 10 + 2 * P.chartSide[1];
expectEqual(beyondSheet > P.sheetSide[1] && beyondSheet - P.chartSide[1] <= P.sheetSide[1], true,
            "two of the widest charts side by side pass the sheet's bound, one does not");
expectThrows(() => preview.contactSheet([wide, wide], sheet, {columns: 2}), "ArgumentError",
             "the sheet of these 2 images would be " + beyondSheet + "x" + (2 * 10 + 22 + P.chartSide[0]) +
             " pixels; expected at most " + P.sheetSide[1] + " along each side");
expectEqual(core.fileExists(sheet), false, "nothing written by the refused sheet");
// An image wider than a sheet can hold is refused by its size (Qt said only
// "Unable to read image data"): a one-row text PPM one pixel too wide.
const wideImage = tmp + "/limits_wide.ppm";
core.writeTextFile(wideImage, "P3\n" + (P.sheetSide[1] + 1) + " 1\n255\n" + "255 255 255\n".repeat(P.sheetSide[1] + 1));
expectThrows(() => preview.contactSheet([wideImage], sheet), "ArgumentError",
             "limits_wide.ppm is " + (P.sheetSide[1] + 1) + "x1 pixels; expected images a sheet can hold, at most " +
             P.sheetSide[1] + " along each side");
expectEqual(core.fileExists(sheet), false, "nothing written for the refused image");

print("limits: ok");
