// core's file functions that runs sharing an output folder rely on:
// fileHash (what --resume compares), removeFile, removeTemporaries (what a
// killed writer leaves) and lockFile (one run per folder).
"use strict";
const [, , tmpDir] = core.scriptArguments();
core.include("test_asserts.js");
core.makePath(tmpDir + "/sub/deeper");

// parseJson: the value, or an error naming the source, line and column.
expectEqual(JSON.stringify(core.parseJson('{"a": [1, "b", {"c": true}]}', "x.json")), '{"a":[1,"b",{"c":true}]}',
            "parseJson's value");
expectThrows(() => core.parseJson('{\n  "a": 1,\n}\n', "map.json"), "InputError", "map.json:3: a trailing comma");
expectThrows(() => core.parseJson("", "empty.json"), "InputError", "empty.json:1: ");
expectThrows(() => core.parseJson('{"a": "\\x"}', "escape.json"), "InputError", "escape.json:1: ");
// Any JSON value, as JSON.parse takes it.
expectEqual(core.parseJson("3", "n"), 3, "a number");
expectEqual(core.parseJson('"Hips"', "s"), "Hips", "a string");
expectEqual(core.parseJson("null", "z"), null, "null");

// SHA-256 of the bytes, as sha256sum prints it (FIPS 180-2's "abc" example).
core.writeTextFile(tmpDir + "/abc.txt", "abc");
expectEqual(core.fileHash(tmpDir + "/abc.txt"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad",
            "fileHash of \"abc\"");
core.writeTextFile(tmpDir + "/fox.txt", "The quick brown fox jumps over the lazy dog");
expectEqual(core.fileHash(tmpDir + "/fox.txt"), "d7a8fbb307d7809469ca9abcb0082e4f8d5651e46d3cdb762d02d0bf37c9e592",
            "fileHash of the fox");
// A binary file: the same bytes the same hash; one mode changed, another.
const mesh = core.loadObject(core.resourcePath() + "/garments/default_skirt.obj");
core.saveObject(mesh, tmpDir + "/skirt.om");
core.saveObject(mesh, tmpDir + "/skirt_again.om");
expectEqual(core.fileHash(tmpDir + "/skirt.om"), core.fileHash(tmpDir + "/skirt_again.om"), "fileHash of one mesh");
multirescloth.setModes(mesh, [0], 2);
core.saveObject(mesh, tmpDir + "/skirt_again.om");
expectEqual(core.fileSize(tmpDir + "/skirt_again.om"), core.fileSize(tmpDir + "/skirt.om"), "size after a mode change");
if (core.fileHash(tmpDir + "/skirt.om") === core.fileHash(tmpDir + "/skirt_again.om"))
  throw new Error("fileHash: a changed binary file of the same size has the same hash");
expectThrows(() => core.fileHash(tmpDir + "/none.txt"), "InputError", "core.fileHash: ", "none.txt", "no such file");
expectThrows(() => core.fileHash(tmpDir + "/sub"), "InputError", "core.fileHash: ", "not a file");

// makePath says why it cannot make a folder (QDir::mkpath says only that it failed).
expectThrows(() => core.makePath(tmpDir + "/fox.txt/inner/folder"), "OutputError", "core.makePath: ",
             "cannot create folder " + tmpDir + "/fox.txt/inner/folder (" + tmpDir + "/fox.txt is a file, not a folder)");

expectThrows(() => core.makePath(tmpDir + "/" + "x".repeat(300)), "OutputError", "core.makePath: ",
             "cannot create folder", "(File name too long)");

// removeFile: true once, then false; a folder is refused.
expectEqual(core.removeFile(tmpDir + "/abc.txt"), true, "removeFile of a file");
expectEqual(core.fileExists(tmpDir + "/abc.txt"), false, "removed file exists");
expectEqual(core.removeFile(tmpDir + "/abc.txt"), false, "removeFile of nothing");
expectThrows(() => core.removeFile(tmpDir + "/sub"), "OutputError", "core.removeFile: ", "/sub", "it is a folder");

// removeTemporaries: the writers' ".NAME.tmp-HEX-N[.EXT]" files in the
// folder itself, nothing else (a subfolder may be another run's output folder).
const temporaries = [".high.om.tmp-1f2e-0.om", ".instance_high.pc2.tmp-abcdef01-12.pc2", ".report.md.tmp-9-3",
                     ".coarse_walk.pc2.tmp-56ae6921-d.pc2"];  // the counter is hex too (a writer's 14th temporary)
const others = [".hidden", "a.tmp-1-0", ".x.tmp-zz-1", ".y.tmp-12", "sub/high.om", "sub/deeper/.tmp-1-0x",
                "sub/.caches.pc2.tmp-1a-0.pc2"];
for (const file of temporaries.concat(others)) core.writeTextFile(tmpDir + "/" + file, "x");
const removed = core.removeTemporaries(tmpDir).map((path) => path.slice(tmpDir.length + 1)).sort();
expectEqual(removed, temporaries.slice().sort(), "removeTemporaries removed");
for (const file of temporaries) expectEqual(core.fileExists(tmpDir + "/" + file), false, file + " exists");
for (const file of others) expectEqual(core.fileExists(tmpDir + "/" + file), true, file + " exists");
expectEqual(core.removeTemporaries(tmpDir + "/no_such_folder"), [], "removeTemporaries of no folder");
// A temporary save_mesh leaves when killed has that form (one is made by hand
// here with the name a save would use: saving succeeds, so leaves none).
expectEqual(core.removeTemporaries(tmpDir), [], "a second sweep");

// An empty text makes an empty file (it was refused as "a non-empty string").
core.writeTextFile(tmpDir + "/empty.txt", "");
expectEqual([core.fileSize(tmpDir + "/empty.txt"), core.readTextFile(tmpDir + "/empty.txt")], [0, ""], "an empty file");
expectThrows(() => core.writeTextFile(tmpDir + "/x.txt", 42), "ArgumentError", "text must be a string");

// lockFile: taken, taken again by the same run; the file exists while held.
expectEqual(core.lockFile(tmpDir + "/sub/.lock"), {locked: true}, "lockFile");
expectEqual(core.lockFile(tmpDir + "/sub/.lock"), {locked: true}, "lockFile again");
expectEqual(core.fileExists(tmpDir + "/sub/.lock"), true, "the lock file exists");
expectThrows(() => core.lockFile(tmpDir + "/no_such_folder/.lock"), "OutputError", "core.lockFile: ", "no_such_folder/.lock",
             "cannot create the lock file (its folder ", "no_such_folder does not exist)");
expectThrows(() => core.lockFile(tmpDir + "/sub/deeper"), "OutputError", "core.lockFile: ", "sub/deeper",
             "cannot create the lock file (it is a folder)");
// A lock file naming no owner (a process killed while creating it), once
// older than a writer needs, is taken over.
core.writeTextFile(tmpDir + "/sub/.ownerless", "\n");
const since = Date.now();
while (Date.now() - since < 3200) {}
expectEqual(core.lockFile(tmpDir + "/sub/.ownerless"), {locked: true}, "lockFile over an ownerless lock");
// Another file (a report, a mistyped path) is no lock, however old: refused,
// left as it was (it was written over, then removed by unlockFile).
core.writeTextFile(tmpDir + "/sub/report.json", "{\"precious\": true}\n");
while (Date.now() - since < 6500) {}
expectThrows(() => core.lockFile(tmpDir + "/sub/report.json"), "ArgumentError", "core.lockFile: ", "sub/report.json",
             " exists and is not a lock file (it names no process)");
expectEqual(core.readTextFile(tmpDir + "/sub/report.json"), "{\"precious\": true}\n", "the file lockFile refused");
// A file whose first line is a number (a live process's, 1) is no lock either: it passed for one.
core.writeTextFile(tmpDir + "/sub/count.txt", "1\n");
expectThrows(() => core.lockFile(tmpDir + "/sub/count.txt"), "ArgumentError", " exists and is not a lock file");
expectEqual(core.readTextFile(tmpDir + "/sub/count.txt"), "1\n", "the counted file lockFile refused");
// unlockFile releases (the file goes), once; a batch of locks one after the other holds one at a time.
expectEqual(core.unlockFile(tmpDir + "/sub/.lock"), true, "unlockFile");
expectEqual(core.fileExists(tmpDir + "/sub/.lock"), false, "the lock file after unlockFile");
expectEqual(core.unlockFile(tmpDir + "/sub/.lock"), false, "unlockFile again");
for (let k = 0; k < 1100; ++k) {  // beyond a 1024-descriptor limit if locks were kept
  expectEqual(core.lockFile(tmpDir + "/sub/.batch").locked, true, "lock " + k);
  expectEqual(core.unlockFile(tmpDir + "/sub/.batch"), true, "unlock " + k);
}
print("core files: ok (" + checked + " errors checked)");
