// Texture coordinates reach what a DCC tool loads: the shared trousers (UV
// seams included) refined once and simulated on the skinned MakeHuman body
// write their UVs into the cache's rest OBJ and every OBJ of the sequence,
// one per face corner, and a coarse vertex keeps the UVs the garment file
// gave it; the body's cache's rest OBJ has base.obj's. Skipped (exit 77) without ../shared/data.
// Arguments: <tests/data> <shared data> <tmp>.
"use strict";
const [, sharedDir, tmpDir] = core.scriptArguments();
core.include("test_asserts.js");
const {garment, clip, body} = sharedMakeHuman(sharedDir, "male_casualsuit04_pants_on_base.obj", "mesh");
core.makePath(tmpDir);

// The OBJ's vt lines and, per face, its corners as [vertex, vt] (0-based).
function readObj(path) {
  const texcoords = [], faces = [];
  for (const line of core.readTextFile(path).split("\n")) {
    const words = line.trim().split(/\s+/);
    if (words[0] === "vt") texcoords.push([Number(words[1]), Number(words[2])]);
    if (words[0] === "f")
      faces.push(words.slice(1).map((corner) => corner.split("/").map((index) => Number(index) - 1)));
  }
  return {texcoords, faces};
}
// Per vertex, the set of UVs its face corners give it ("u v" strings).
function uvsByVertex(obj) {
  const byVertex = new Map();
  for (const face of obj.faces)
    for (const [vertex, vt] of face) {
      if (!byVertex.has(vertex)) byVertex.set(vertex, new Set());
      byVertex.get(vertex).add(obj.texcoords[vt].join(" "));
    }
  return byVertex;
}

const coarse = core.loadObject(garment, {units: "dm"});
const fine = multirescloth.refineUniform(coarse, 1);
expectEqual([core.objectInfo(coarse).textureCoordinates, core.objectInfo(fine).textureCoordinates], [true, true],
            "objectInfo says the garment and its refinement have UVs");
expectEqual(core.objectInfo(core.loadObject(core.resourcePath() + "/garments/default_skirt.obj")).textureCoordinates,
            false, "the embedded skirt has none");
const report = multirescloth.simulate(fine, {
  motion: {path: clip, units: "cmu"}, body: body, place: "makehuman", preroll: 0.1, frames: 2, fitWarning: false,
  output: tmpDir + "/trousers.pc2", objSequence: tmpDir + "/trousers", bodyOutput: tmpDir + "/body.pc2"});
expectEqual([report.restMesh, report.objFiles.length], [tmpDir + "/trousers.obj", 2], "rest OBJ and sequence written");
const source = uvsByVertex(readObj(garment));
for (const path of [report.restMesh].concat(report.objFiles)) {
  const obj = readObj(path);
  const corners = obj.faces.reduce((sum, face) => sum + face.length, 0);
  expectEqual([obj.texcoords.length, obj.faces.every((face) => face.every(([, vt]) => vt >= 0))], [corners, true],
              path + ": one vt per face corner");
  // The coarse vertices come first, in the file's order: each keeps its
  // UVs (two or more on a seam).
  const written = uvsByVertex(obj);
  let checked = 0;
  for (const [vertex, uvs] of source) {
    const mine = written.get(vertex);
    expectEqual([...mine].sort(), [...uvs].map((uv) => uv.split(" ").map(Number).join(" ")).sort(),
                path + ": vertex " + vertex + "'s UVs");
    ++checked;
  }
  if (checked < 800) throw new Error(path + ": only " + checked + " coarse vertices checked");
}
// exportSurface at a frame of the cache: the sequence's frame, to the
// cache's single precision, with the same texture coordinates.
const points = (path) => core.readTextFile(path).split("\n").filter((line) => line.startsWith("v "))
                             .map((line) => line.trim().split(/\s+/).slice(1).map(Number));
multirescloth.exportSurface(fine, tmpDir + "/frame1.obj", {cache: report.output, frame: 1});
const exported = points(tmpDir + "/frame1.obj"), sequenced = points(report.objFiles[1]);
expectEqual(exported.length, sequenced.length, "vertices at frame 1");
let farthest = 0;
exported.forEach((p, i) => p.forEach((x, k) => { farthest = Math.max(farthest, Math.abs(x - sequenced[i][k])); }));
expectAtMost(farthest, 1e-5, "exported frame against the sequence's (m; the PC2 holds floats)");
expectEqual(readObj(tmpDir + "/frame1.obj").texcoords.length, readObj(report.objFiles[1]).texcoords.length,
            "the exported frame's texture coordinates");
// Triangulated, every frame has the rest mesh's triangles (a sequence for a
// DCC tool needs one topology; the diagonals flipped from frame to frame).
const faceLines = (path) => core.readTextFile(path).split("\n").filter((line) => line.startsWith("f "));
multirescloth.exportSurface(fine, tmpDir + "/rest_tri.obj", {triangulate: true});
const restTriangles = faceLines(tmpDir + "/rest_tri.obj");
for (const frame of [0, 1]) {
  multirescloth.exportSurface(fine, tmpDir + "/tri" + frame + ".obj", {cache: report.output, frame: frame, triangulate: true});
  const triangles = faceLines(tmpDir + "/tri" + frame + ".obj");
  expectEqual([triangles.length, triangles.filter((line, k) => line !== restTriangles[k]).length],
              [restTriangles.length, 0], "frame " + frame + "'s triangles: how many, how many not the rest mesh's");
}
expectThrows(() => multirescloth.exportSurface(fine, tmpDir + "/x.obj", {frame: 1}), "ArgumentError",
             "option 'frame' needs option 'cache'");
expectThrows(() => multirescloth.exportSurface(fine, tmpDir + "/x.obj", {cache: report.bodyCache}), "ArgumentError",
             "option 'cache': ", "points per frame", "vertices (a cache of another mesh?)");
expectThrows(() => multirescloth.exportSurface(fine, tmpDir + "/x.obj", {cache: report.output, frame: 9}), "ArgumentError",
             "frame 9 is out of range (the cache has 2 frames)");
expectEqual(core.fileExists(tmpDir + "/x.obj"), false, "nothing written by a refused export");

// The body's rest OBJ carries base.obj's UVs too (its bridges' and mittens'
// capsules the texture's corner), one per face corner. It is drawn as it
// collides: base.obj's 26,756 triangles less the hands', the wrists capped.
const bodyObj = readObj(report.bodyMesh);
const bodyCorners = bodyObj.faces.reduce((sum, face) => sum + face.length, 0);
expectEqual([bodyObj.texcoords.length, bodyObj.faces.every((face) => face.every(([, vt]) => vt >= 0))],
            [bodyCorners, true], report.bodyMesh + ": one vt per face corner");
if (!(bodyObj.faces.length >= 20000 && bodyObj.faces.length < 26756))
  throw new Error(report.bodyMesh + ": " + bodyObj.faces.length + " faces; expected the body less its hands");
// Every vertex of the body's OBJ is one a face uses (Blender's importer
// drops the others, the hands the mittens replace, and the cache would no
// longer match what it imported), and its cache holds that many points.
const bodyVertices = core.readTextFile(report.bodyMesh).split("\n").filter((line) => line.startsWith("v ")).length;
const used = new Array(bodyVertices).fill(false);
for (const face of bodyObj.faces) for (const [vertex] of face) used[vertex] = true;
expectEqual([used.filter((u) => u).length, core.fileSize(report.bodyCache)], [bodyVertices, 32 + 12 * bodyVertices * 2],
            report.bodyMesh + ": vertices used by faces; its cache's size (2 frames)");
print("texture coordinates: ok");
