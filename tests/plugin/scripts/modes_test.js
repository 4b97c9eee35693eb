// setModes / paintModes / getModes on the 3 x 3 unit grid (vertex (x, y) has
// index 4 * y + x).
"use strict";
const [dataDir] = core.scriptArguments();

core.include("test_asserts.js");

const grid = core.loadObject(dataDir + "/grid3x3.obj");
expectEqual(multirescloth.getModes(grid), Array(16).fill(1), "default modes");

expectEqual(multirescloth.setModes(grid, [0, 15], 4), 2, "setModes returns the number of ids");
expectEqual(multirescloth.setModes(grid, [], 4), 0, "an empty list is fine");
let modes = multirescloth.getModes(grid);
expectEqual([modes[0], modes[15], modes[1]], [4, 4, 1], "setModes sets exactly the given vertices");

// A sphere of radius 1 around (1, 1, 0) holds (1,1) and its 4 grid
// neighbours at distance 1 (the radius is inclusive).
expectEqual(multirescloth.paintModes(grid, {center: [1, 1, 0], radius: 1, mode: 3}), 5, "painted count");
modes = multirescloth.getModes(grid);
const painted = [];
modes.forEach((mode, vertex) => { if (mode === 3) painted.push(vertex); });
expectEqual(painted, [1, 4, 5, 6, 9], "painted vertices");
expectEqual(modes[0], 4, "outside the brush: unchanged");

// Radius 0 paints only a vertex exactly at the centre; a centre off the mesh paints nothing.
expectEqual(multirescloth.paintModes(grid, {center: [3, 3, 0], radius: 0, mode: 2}), 1, "radius 0 on a vertex");
expectEqual(multirescloth.paintModes(grid, {center: [10, 10, 10], radius: 1, mode: 2}), 0, "brush off the mesh");
expectEqual(multirescloth.getModes(grid)[15], 2, "radius 0 painted vertex 15");

// Mode counts in objectInfo follow the layer: element m counts mode m.
expectEqual(core.objectInfo(grid).verticesPerMode, [0, 9, 1, 5, 1], "verticesPerMode");
print("modes: ok");
