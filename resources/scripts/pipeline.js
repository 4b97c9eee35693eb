// mrcloth pipeline: the whole method in one run, through the public
// scripting API only (`mrcloth pipeline [options]` runs this same file).
//
//   coarse garment -> uniform refinement (high-resolution mesh)
//   -> instance: the high-resolution garment on the instance motion (PC2)
//   -> deformation modes from its curvature, mapped onto the coarse garment
//   -> adaptive refinement, one multi-resolution mesh per threshold delta
//   -> every test motion on: coarse, each multi-resolution mesh, high, and a
//      uniform mesh of about the multi-resolution vertex count
//   -> meshes (.om, PLY), caches (PC2 + rest OBJ, body caches), previews,
//      plots, report.md and report.json
//
// Every stage writes its files atomically and then a record in
// <out>/stages/<stage>.json; with --resume a stage whose record and files
// exist is not run again. Ctrl-C stops between steps (exit 130) and leaves
// only complete files. Run `mrcloth pipeline --help` for the options.
"use strict";

const resources = core.resourcePath();
const USAGE = [
  "Usage: mrcloth pipeline [options]        (or: mrcloth -b pipeline.js -- [options])",
  "",
  "Runs the whole method: refine, record the instance, extract and map modes, refine",
  "adaptively, simulate every test motion on every model, export, render and report.",
  "Without options it runs on the embedded default (skirt, mannequin, walks).",
  "",
  "Inputs:",
  "  --garment FILE         coarse quad garment (.obj/.om/...) [embedded default skirt]",
  "  --units U              the garment's units: m, dm, cm, mm, inch [m; dm with --makehuman]",
  "  --makehuman DIR        a MakeHuman body folder (base.obj, rigs/cmu_mb.mhskel,",
  "                         rigs/default_weights.mhw): fits the capsules, or is the body",
  "  --body B               capsules | mesh (the skinned MakeHuman mesh) [capsules]",
  "  --place P              none | makehuman | firstFrame [makehuman with --makehuman, else firstFrame]",
  "  --waist-smoothing M    with --makehuman: metres along the waist over which its pins' skin weights",
  "                         are averaged, so the band keeps its length where skinning stretches the",
  "                         skin; 0: each pin as the skin under it (body.waistSmoothing; README) [0.02]",
  "  --instance FILE        BVH of the instance motion [embedded walk_instance.bvh]",
  "  --test FILE[,FILE...]  BVH test motions; repeatable [embedded walk_new.bvh,squat.bvh]",
  "  --motion-units U       m, cmu, dm, cm, mm, inch, or auto (per file, the units giving an adult's legs):",
  "                         the BVH files' units [m]",
  "  --motion-positions P   absolute | relative: the BVH position channels are each joint's translation",
  "                         (its OFFSET only where it rests; Blender, MotionBuilder) or are added to",
  "                         the OFFSET; CMU clips read alike either way [absolute]",
  "  --joint-map FILE       JSON {\"name in the clip\": \"CMU name\", ...} for clips whose joints the",
  "                         automatic renaming (CMU, DAZ/Poser, Mixamo) does not know [automatic]",
  "Method:",
  "  --levels N             uniform refinements of the high-resolution mesh, >= 1 [2]",
  "  --modes N              deformation modes (k-means clusters), >= 1 [3]",
  "  --delta D[,D...]       adaptive thresholds, one multi-resolution mesh each, > 0 [5,7]",
  "  --map-modes M          index | highest | frequent: how the instance's modes reach the coarse garment",
  "                         (index: coarse vertex i takes high vertex i's, the paper's rule; highest /",
  "                         frequent: the highest / most frequent mode in its cell) [index]",
  "  --material M           cotton | denim | silk [cotton]",
  "  --t-node-sag           experimental: the limiter reads a spring from a T-node from where the fine",
  "                         row beside it would put the T-node (simulate's tNodeSag; README) [off]",
  "  --newton-cg K          each solve iteration a Newton step by K conjugate-gradient iterations, >= 0;",
  "                         less damped, costlier (simulate's newtonCg; README) [0: the plain iteration]",
  "  --bend-model M         distance | secondDifference: experimental bend springs quadratic in the",
  "                         curvature (simulate's bendModel; give --bend-stiffness) [distance, the paper's]",
  "  --bend-stiffness K     bend spring stiffness at level 1, N/m, >= 0 [the material's]",
  "  --limiter-acceleration A",
  "                         the strain limiter's Chebyshev estimate: a number in [0, 1) (0: plain sweeps),",
  "                         or auto (raised to the garment's chain's; simulate's limiterAcceleration;",
  "                         README, Collision cost) [simulate's default, auto]",
  "  --fps F                output frames per second, > 0 [30]",
  "  --step-rate HZ         simulation steps per second, >= --fps; fewer are cheaper and stretch more",
  "                         (README, Characters) [120, the CMU mocap rate]",
  "  --instance-frames N    recorded instance frames, >= 2 [200]",
  "  --test-frames N        frames per test motion, >= 1 [60]",
  "  --preroll S            seconds from the rest pose to each motion's start, >= 0 [1]",
  "  --threads N            threads resolving collisions, >= 0 (0: one per core); the same results,",
  "                         but the reported times are then no longer one core's [1]",
  "Output:",
  "  --out DIR              output folder, created if missing [pipeline_out]",
  "  --resume               skip stages whose outputs are complete (same options only)",
  "  --size WxH             preview image size in pixels [800x800]",
  "  --sequence             also render every frame of each test motion's first multi-resolution run",
  "                         (and an animated GIF of it when ImageMagick's convert is installed)",
  "  --obj-sequence         also write every simulated frame as OBJ (caches/<run>_0000.obj ...)",
  "  -q, --quiet            no progress (host option)",
  "  -h, --help             this text",
].join("\n");

// --- Options -----------------------------------------------------------------

function pipelineError(message, name = "ArgumentError") {
  const error = new Error("pipeline: " + message);
  error.name = name;
  return error;
}

const DEFAULTS = {
  garment: resources + "/garments/default_skirt.obj", units: null, makehuman: "", body: "capsules", place: null,
  instance: resources + "/characters/walk_instance.bvh",
  test: [resources + "/characters/walk_new.bvh", resources + "/characters/squat.bvh"], motionUnits: "m",
  motionPositions: "absolute", jointMap: "",
  levels: 2, modes: 3, delta: [5, 7], mapModes: "index", material: "cotton", fps: 30, instanceFrames: 200, testFrames: 60,
  preroll: 1, threads: 1, out: "pipeline_out", resume: false, size: [800, 800], sequence: false, objSequence: false, help: false,
  tNodeSag: false, stepRate: null,  // null: simulate's default, the mocap rate
  waistSmoothing: 0.02,  // simulate's default; recorded with --makehuman, so runs made before it (0 in effect) do not resume
  newtonCg: 0, bendModel: "distance", bendStiffness: null,  // null: the material's
  limiterAcceleration: null,  // null: simulate's default
};
const FLAGS = {"--resume": "resume", "--sequence": "sequence", "--obj-sequence": "objSequence", "--help": "help",
               "-h": "help", "--t-node-sag": "tNodeSag"};
const VALUED = {
  "--garment": "garment", "--units": "units", "--makehuman": "makehuman", "--body": "body", "--place": "place",
  "--instance": "instance", "--test": "test", "--motion-units": "motionUnits", "--levels": "levels",
  "--motion-positions": "motionPositions", "--joint-map": "jointMap",
  "--modes": "modes", "--delta": "delta", "--map-modes": "mapModes", "--material": "material", "--fps": "fps",
  "--instance-frames": "instanceFrames", "--test-frames": "testFrames", "--preroll": "preroll", "--out": "out",
  "--threads": "threads", "--step-rate": "stepRate", "--newton-cg": "newtonCg", "--bend-model": "bendModel",
  "--bend-stiffness": "bendStiffness", "--waist-smoothing": "waistSmoothing",
  "--limiter-acceleration": "limiterAcceleration",
  "--size": "size",
};
const UNITS = ["m", "dm", "cm", "mm", "inch"];

function integerOption(name, text, least) {
  const value = Number(text);
  if (!/^[+]?\d+$/.test(text.trim()) || value < least)
    throw pipelineError("option " + name + ": expected an integer >= " + least + ", got \"" + text + "\"");
  return value;
}
function numberOption(name, text, least, strictly) {
  const value = Number(text);
  if (text.trim() === "" || !isFinite(value) || (strictly ? value <= least : value < least))
    throw pipelineError("option " + name + ": expected a number " + (strictly ? "> " : ">= ") + least + ", got \"" +
                        text + "\"");
  return value;
}
function choiceOption(name, text, choices) {
  if (choices.indexOf(text) < 0)
    throw pipelineError("option " + name + ": expected one of " + choices.join(", ") + ", got \"" + text + "\"");
  return text;
}

/// Parses `--name value`, `--name=value` and flags; the last of a repeated
/// option wins except --test, which accumulates.
function parseOptions(args) {
  const options = Object.assign({}, DEFAULTS);
  let tests = null, waistGiven = false;
  for (let i = 0; i < args.length; ++i) {
    const argument = args[i];
    const equals = argument.startsWith("--") ? argument.indexOf("=") : -1;
    const name = equals < 0 ? argument : argument.slice(0, equals);
    if (FLAGS[name] !== undefined) {
      if (equals >= 0) throw pipelineError("option " + name + " takes no value");
      options[FLAGS[name]] = true;
      continue;
    }
    const key = VALUED[name];
    if (key === undefined)
      throw pipelineError((argument.startsWith("-") ? "unknown option " : "unexpected argument ") + "\"" + argument +
                          "\" (mrcloth pipeline --help lists the options)");
    let text;
    if (equals >= 0) text = argument.slice(equals + 1);
    else if (i + 1 < args.length) text = args[++i];
    else throw pipelineError("option " + name + " needs a value");
    switch (key) {
      case "levels": options.levels = integerOption(name, text, 1); break;
      case "modes": options.modes = integerOption(name, text, 1); break;
      case "instanceFrames": options.instanceFrames = integerOption(name, text, 2); break;
      case "testFrames": options.testFrames = integerOption(name, text, 1); break;
      case "threads": options.threads = integerOption(name, text, 0); break;
      case "fps": options.fps = numberOption(name, text, 0, true); break;
      case "preroll": options.preroll = numberOption(name, text, 0, false); break;
      case "stepRate": options.stepRate = numberOption(name, text, 0, true); break;
      case "newtonCg": options.newtonCg = integerOption(name, text, 0); break;
      case "bendModel": options.bendModel = choiceOption(name, text, ["distance", "secondDifference"]); break;
      case "bendStiffness": options.bendStiffness = numberOption(name, text, 0, false); break;
      case "limiterAcceleration": {
        const value = Number(text);
        if (text !== "auto" && (text.trim() === "" || !isFinite(value) || value < 0 || value >= 1))
          throw pipelineError("option " + name + ": expected auto or a number >= 0 and < 1, got \"" + text + "\"");
        options.limiterAcceleration = text === "auto" ? text : value;
        break;
      }
      case "waistSmoothing":
        options.waistSmoothing = numberOption(name, text, 0, false);
        waistGiven = true;
        break;
      case "delta": {
        const values = text.split(",").map((part) => numberOption(name, part, 0, true));
        options.delta = values.filter((value, k) => values.indexOf(value) === k);
        break;
      }
      case "test":
        if (tests === null) tests = [];
        for (const part of text.split(",")) {
          if (part === "") throw pipelineError("option " + name + ": empty file name in \"" + text + "\"");
          tests.push(part);
        }
        break;
      case "units": options.units = choiceOption(name, text, UNITS); break;
      case "motionUnits": options.motionUnits = choiceOption(name, text, ["m", "cmu", "dm", "cm", "mm", "inch", "auto"]); break;
      case "motionPositions": options.motionPositions = choiceOption(name, text, ["absolute", "relative"]); break;
      case "body": options.body = choiceOption(name, text, ["capsules", "mesh"]); break;
      case "place": options.place = choiceOption(name, text, ["none", "makehuman", "firstFrame"]); break;
      case "material": options.material = choiceOption(name, text, ["cotton", "denim", "silk"]); break;
      case "mapModes": options.mapModes = choiceOption(name, text, ["index", "highest", "frequent"]); break;
      case "size": {
        const match = /^(\d+)x(\d+)$/.exec(text);
        if (!match || Number(match[1]) < 64 || Number(match[2]) < 64 || Number(match[1]) > 8192 || Number(match[2]) > 8192)
          throw pipelineError("option " + name + ": expected WIDTHxHEIGHT in pixels, 64..8192 each, got \"" + text + "\"");
        options.size = [Number(match[1]), Number(match[2])];
        break;
      }
      default:
        if (text === "") throw pipelineError("option " + name + ": empty value");
        options[key] = text;
    }
  }
  if (tests !== null) options.test = tests;
  // Caches and stage records are named after the motion's file name.
  const names = options.test.map(baseName);
  names.forEach((name, k) => {
    const first = names.indexOf(name);
    if (first !== k)
      throw pipelineError("option --test: " + options.test[first] + " and " + options.test[k] + " share the name \"" +
                          name + "\", which names their caches; rename one");
  });
  if (options.stepRate !== null && options.stepRate < options.fps)
    throw pipelineError("option --step-rate: expected at least --fps (" + options.fps + " frames per second), got " +
                        options.stepRate);
  if (options.jointMap) options.joints = readJointMap(options.jointMap);
  if (options.units === null) options.units = options.makehuman ? "dm" : "m";
  if (options.place === null) options.place = options.makehuman ? "makehuman" : "firstFrame";
  if (options.body === "mesh" && !options.makehuman)
    throw pipelineError("option --body mesh needs --makehuman DIR (the skinned MakeHuman body)");
  if (waistGiven && !options.makehuman)
    throw pipelineError("option --waist-smoothing needs --makehuman DIR (the body whose skin the waist follows)");
  if (options.place === "makehuman" && !options.makehuman)
    throw pipelineError("option --place makehuman needs --makehuman DIR (the body the garment was modelled on)");
  return options;
}

/// The clips' joint map read from its JSON file: an object of names to names.
function readJointMap(path) {
  if (!core.fileExists(path)) throw pipelineError("option --joint-map: no such file: " + path);
  if (!core.fileReadable(path)) throw pipelineError("option --joint-map: cannot read " + path);
  let map;
  try {
    map = JSON.parse(core.readTextFile(path));
  } catch (error) {
    throw pipelineError("option --joint-map: " + path + " is not JSON (" + error.message +
                        "); expected {\"name in the clip\": \"CMU name\", ...}");
  }
  if (map === null || typeof map !== "object" || Array.isArray(map))
    throw pipelineError("option --joint-map: " + path + " holds " + (Array.isArray(map) ? "an array" : typeof map) +
                        "; expected an object {\"name in the clip\": \"CMU name\", ...}");
  for (const [from, to] of Object.entries(map))
    if (typeof to !== "string")
      throw pipelineError("option --joint-map: " + path + ": \"" + from + "\" maps to " + JSON.stringify(to) +
                          "; expected a joint name (a string)");
  return map;
}

/// A clip's joint names as in its file (its units only matter to the size
/// check, which a clip of unknown names passes in metres).
const fileJointNames = {};
function jointsInFile(options, path) {
  if (!(path in fileJointNames)) {
    const read = (units) => multirescloth.motionInfo(
        {path: path, units: units, positions: options.motionPositions, joints: "asIs", axes: "asIs"}).joints;
    try {
      fileJointNames[path] = read(options.motionUnits);
    } catch (error) {
      fileJointNames[path] = read("m");
    }
  }
  return fileJointNames[path];
}

/// How every run reads a clip: simulate's `motion` option. The joint map's
/// names a clip has rename them; a clip with none of them is named
/// automatically (the embedded walks beside a clip of other names).
function motionOption(options, path) {
  const motion = {path: path, units: options.motionUnits, positions: options.motionPositions};
  if (options.joints) {
    const names = jointsInFile(options, path);
    const own = {};
    for (const [from, to] of Object.entries(options.joints))
      if (names.includes(from)) own[from] = to;
    if (Object.keys(own).length > 0) motion.joints = own;
  }
  return motion;
}

/// Every input must exist and be readable before any work starts.
function checkInputs(options) {
  const inputs = [["--garment", options.garment], ["--instance", options.instance]];
  for (const test of options.test) inputs.push(["--test", test]);
  if (options.makehuman)
    for (const file of makehumanFiles(options.makehuman)) inputs.push(["--makehuman", file]);
  for (const [name, path] of inputs) {
    if (!core.fileExists(path)) throw pipelineError("option " + name + ": no such file: " + path);
    if (!core.fileReadable(path)) throw pipelineError("option " + name + ": cannot read " + path);
  }
  // Every clip read and its figure sized now, not after the instance's hours:
  // a clip in the wrong units is refused with the units that would fit.
  const clips = inputs.filter(([name]) => name === "--instance" || name === "--test");
  if (options.joints) {
    const named = new Set();
    for (const [, path] of clips) jointsInFile(options, path).forEach((joint) => named.add(joint));
    const unknown = Object.keys(options.joints).filter((from) => !named.has(from));
    if (unknown.length > 0)
      throw pipelineError("option --joint-map: " + options.jointMap + " renames " +
                          unknown.map((from) => "\"" + from + "\"").join(", ") + ", a joint of none of the clips",
                          "InputError");
  }
  for (const [name, path] of clips) {
    let info;
    try {
      info = multirescloth.motionInfo(motionOption(options, path));
    } catch (error) {
      throw pipelineError("option " + name + ": " + error.message.replace(/^multirescloth\.motionInfo: option 'motion': /, ""),
                          error.name);
    }
    // The waist follows the pelvis: a clip without it fails only at its run.
    if (!info.joints.includes("Hips")) {
      const shown = info.joints.slice(0, 8).join(", ") + (info.joints.length > 8 ? ", ..." : "");
      throw pipelineError("option " + name + ": " + path + " has no joint 'Hips' (after renaming), which the pinned " +
                          "waist follows; its joints: " + shown + "; expected CMU, DAZ/Poser or Mixamo names, or " +
                          "give --joint-map FILE.json {\"its pelvis\": \"Hips\", ...}", "InputError");
    }
  }
}

function makehumanFiles(folder) {
  return [folder + "/base.obj", folder + "/rigs/cmu_mb.mhskel", folder + "/rigs/default_weights.mhw"];
}

// --- Files and stages ------------------------------------------------------------

function baseName(path) {
  return path.split("/").pop().replace(/\.[^.]*$/, "");
}

/// The defaults that decide results, by revision: a run resumes only what
/// the same revision made. Bump it with a change of default that moves
/// results without an option saying so. 2: the limiter's estimate from the
/// garment's chain (861bb6d); before it (no revision recorded), 0.97.
const SOLVER_REVISION = 2;

/// What decides the results: a resumed run must have been started with the same.
function resultOptions(options) {
  const copy = Object.assign({solverRevision: SOLVER_REVISION}, options);
  delete copy.resume;
  delete copy.help;
  delete copy.out;
  if (copy.stepRate === null) delete copy.stepRate;  // runs from before --step-rate still resume
  // Likewise runs from before the solve and bend options, at their defaults.
  if (copy.newtonCg === 0) delete copy.newtonCg;
  if (copy.bendModel === "distance") delete copy.bendModel;
  if (copy.bendStiffness === null) delete copy.bendStiffness;
  if (copy.limiterAcceleration === null) delete copy.limiterAcceleration;
  // Runs from before the clips' reading options, read as these defaults do.
  if (copy.motionPositions === "absolute") delete copy.motionPositions;
  if (!copy.jointMap) {
    delete copy.jointMap;
    delete copy.joints;
  }
  if (!copy.makehuman) delete copy.waistSmoothing;  // no skin to follow: it decides nothing
  return copy;
}

class Stages {
  constructor(out, options, total) {
    this.out = out;
    this.total = total;  // stages this run has, for the "[k/total]" in progress lines
    this.folder = out + "/stages";
    this.resume = options.resume;
    this.skipped = [];
    this.ran = [];
    core.makePath(this.folder);
    const configPath = this.folder + "/options.json";
    const wanted = JSON.stringify(resultOptions(options));
    if (this.resume && core.fileExists(configPath)) {
      const previous = core.readTextFile(configPath);
      if (previous !== wanted) {
        const before = JSON.parse(previous), now = JSON.parse(wanted);
        const differing = Object.keys(now).filter((key) => JSON.stringify(before[key]) !== JSON.stringify(now[key]));
        if (differing.includes("solverRevision"))
          throw pipelineError("--resume: " + out + " holds a run made with other solver defaults (revision " +
                              (before.solverRevision === undefined ? 1 : before.solverRevision) + "; this build's " +
                              SOLVER_REVISION + "), whose results would mix with new ones; run without --resume or " +
                              "use another --out");
        throw pipelineError("--resume: " + out + " holds a run with other options (" + differing.join(", ") +
                            "); run without --resume or use another --out");
      }
    }
    core.writeTextFile(configPath, wanted);
  }

  /// Runs `work` (which returns the stage's record) unless resuming finds
  /// the record and every file in `outputs` (relative to the output folder).
  run(name, outputs, work) {
    const recordPath = this.folder + "/" + name + ".json";
    const label = "pipeline [" + (this.ran.length + this.skipped.length + 1) + "/" + this.total + "] " + name;
    if (this.resume && core.fileExists(recordPath) && outputs.every((file) => core.fileExists(this.out + "/" + file))) {
      core.log(label + ": complete from an earlier run, skipped");
      this.skipped.push(name);
      return JSON.parse(core.readTextFile(recordPath));
    }
    core.log(label + " ...");
    const started = Date.now();
    const record = work();
    record.stageSeconds = (Date.now() - started) / 1000;
    record.outputs = outputs;
    core.writeTextFile(recordPath, JSON.stringify(record, null, 1) + "\n");
    this.ran.push(name);
    return record;
  }
}

// --- The run ---------------------------------------------------------------------

// Users of the command meet its errors as a command's: the message (which
// names the option, file or line at fault), not this script's stack. Errors
// of other kinds (a TypeError is a bug here) keep their stack.
const REPORTED_ERRORS = ["ArgumentError", "InputError", "OutputError", "Error"];
try {
  const options = parseOptions(core.scriptArguments());
  if (options.help) {
    print(USAGE);
  } else {
    checkInputs(options);
    runPipeline(options);
  }
} catch (error) {
  if (!(error instanceof Error) || !REPORTED_ERRORS.includes(error.name)) throw error;
  console.error(error.name + ": " + error.message);
  core.exitApplication(1);
}

/// A garment in the wrong units (centimetres read as metres: a 54 m skirt)
/// is refused before any work, with the units that would fit: the span
/// multirescloth.simulate accepts on a character (kGarmentSpanLow/High).
function checkGarmentSize(options, info) {
  const [low, high] = [0.1, 4.0];
  const span = Math.max(...[0, 1, 2].map((k) => info.bbox.max[k] - info.bbox.min[k]));
  if (span >= low && span <= high) return;
  const metres = {m: 1, dm: 0.1, cm: 0.01, mm: 0.001, inch: 0.0254};
  const fitting = Object.keys(metres).filter((units) => {
    const there = span / metres[options.units] * metres[units];
    return units !== options.units && there >= low && there <= high;
  });
  const hint = fitting.length > 0 ? " (in '" + fitting[0] + "' it spans " +
                                     (span / metres[options.units] * metres[fitting[0]]).toFixed(2) + " m)" : "";
  throw pipelineError("option --units: " + options.garment + " read in '" + options.units + "' spans " +
                      span.toPrecision(3) + " m (its bounding box's largest side); expected " + low + "-" + high +
                      " m for a garment worn by a person: check the units" + hint, "InputError");
}

function runPipeline(options) {
  const out = options.out;
  // The garment is read before anything is written: a broken file stops the run here.
  const coarse = core.loadObject(options.garment, {units: options.units});
  const coarseInfo = core.objectInfo(coarse);
  checkGarmentSize(options, coarseInfo);
  // The waist is the highest opening; a closed surface has none to pin.
  if (coarseInfo.boundaryLoops === 0)
    throw pipelineError("option --garment: " + options.garment + " is a closed surface (no boundary loop); expected " +
                        "a garment with openings, the highest of which is pinned as its waist", "InputError");
  // Refined again, an already refined mesh would make every model the same.
  if (coarseInfo.maxLevel > 1)
    throw pipelineError("option --garment: " + options.garment + " is already refined (its faces reach level " +
                        coarseInfo.maxLevel + "); expected the coarse garment the method starts from", "InputError");
  core.makePath(out);
  for (const folder of ["meshes", "caches", "previews", "plots"]) core.makePath(out + "/" + folder);
  // refine-uniform, instance, modes, refine-adaptive, refine-equal, previews, and
  // per test motion one simulation per model (the equal-size uniform mesh
  // counted) and a comparison; corrected once the models are known.
  const stages = new Stages(out, options, 6 + options.test.length * (4 + options.delta.length));
  const started = Date.now();

  const makehuman = options.makehuman ? makehumanFiles(options.makehuman) : null;
  const body = makehuman ? {type: options.body, obj: makehuman[0], skeleton: makehuman[1], weights: makehuman[2],
                            waistSmoothing: options.waistSmoothing}
                         : options.body;
  const motion = (path) => motionOption(options, path);
  // What a run on the character is given besides its motion and files.
  const material = options.bendStiffness === null ? options.material
                                                   : {preset: options.material, bendStiffness: options.bendStiffness};
  const characterSettings = (frames) => Object.assign(
      {body: body, place: options.place, frames: frames, fps: options.fps, preroll: options.preroll,
       material: material, tNodeSag: options.tNodeSag, threads: options.threads},
      options.stepRate === null ? {} : {stepRate: options.stepRate},
      options.newtonCg === 0 ? {} : {newtonCg: options.newtonCg},
      options.bendModel === "distance" ? {} : {bendModel: options.bendModel},
      options.limiterAcceleration === null ? {} : {limiterAcceleration: options.limiterAcceleration});
  const onCharacter = (frames, output, bodyOutput) => {
    const settings = Object.assign({motion: null}, characterSettings(frames), {output: out + "/" + output});
    if (bodyOutput) settings.bodyOutput = out + "/" + bodyOutput;
    return settings;
  };
  const simulationNumbers = (report) => ({
    vertices: report.vertices, frames: report.frames, msPerFrame: report.msPerFrame,
    perFrameMs: report.perFrameMs, maxStretch: report.maxStretch, maxTearOpening: report.maxTearOpening,
    maxClothStretch: report.maxClothStretch, stretchPinned: report.mostStretched.pinned,
    maxPenetration: report.maxPenetration, maxClothPenetration: report.maxClothPenetration,
    penetrationPinned: report.deepest.pinned, maxFaceDepth: report.maxFaceDepth,
    meanRounds: report.meanRounds, garmentCleared: report.garmentCleared, maxWaistError: report.maxWaistError,
    nonFinite: report.nonFinite, preroll: report.preroll.msPerFrame, stepRate: report.stepRate,
  });
  const mustFinish = (what, report) => {
    if (report.cancelled) throw new Error("pipeline: " + what + " was cancelled");
    if (report.nonFinite) throw new Error("pipeline: " + what + " became non-finite (NaN); nothing was written");
  };

  // Stage 1: the high-resolution mesh.
  const highRecord = stages.run("refine-uniform", ["meshes/high.om", "meshes/high_by_level.ply"], () => {
    const id = multirescloth.refineUniform(coarse, options.levels);
    const report = multirescloth.lastReport();
    core.saveObject(id, out + "/meshes/high.om");
    multirescloth.exportSurface(id, out + "/meshes/high_by_level.ply", {colorBy: "level"});
    core.deleteObject(id);
    return {vertices: report.vertices, faces: report.faces, verticesPerLevel: report.verticesPerLevel,
            milliseconds: report.milliseconds};
  });
  let high = core.loadObject(out + "/meshes/high.om");

  // Stage 2: the instance.
  const instanceRecord = stages.run("instance", ["caches/instance_high.pc2", "caches/instance_high.obj",
                                                 "caches/instance_body.pc2", "caches/instance_body.obj"], () => {
    const settings = onCharacter(options.instanceFrames, "caches/instance_high.pc2", "caches/instance_body.pc2");
    settings.motion = motion(options.instance);
    const wall = Date.now();
    const report = multirescloth.recordInstance(high, settings);
    mustFinish("the instance", report);
    const numbers = simulationNumbers(report);
    numbers.seconds = (Date.now() - wall) / 1000;
    numbers.motion = options.instance;
    return numbers;
  });

  // Stage 3: modes, extracted on the high-resolution mesh and mapped to the coarse one.
  const modesRecord = stages.run("modes", ["meshes/high_modes.om", "meshes/coarse_modes.om",
                                           "meshes/high_by_mode.ply", "meshes/high_by_curvature.ply",
                                           "meshes/coarse_by_mode.ply", "meshes/coarse_layers.csv"], () => {
    const extraction = multirescloth.extractModes(high, out + "/caches/instance_high.pc2", {clusters: options.modes});
    const mapping = multirescloth.mapModes(high, coarse, {method: options.mapModes});
    core.saveObject(high, out + "/meshes/high_modes.om");
    core.saveObject(coarse, out + "/meshes/coarse_modes.om");
    multirescloth.exportSurface(high, out + "/meshes/high_by_mode.ply", {colorBy: "mode"});
    multirescloth.exportSurface(high, out + "/meshes/high_by_curvature.ply", {colorBy: "curvature"});
    multirescloth.exportSurface(coarse, out + "/meshes/coarse_by_mode.ply", {colorBy: "mode"});
    multirescloth.saveLayers(coarse, out + "/meshes/coarse_layers.csv");
    return {sizes: extraction.sizes, centroids: extraction.centroids, milliseconds: extraction.milliseconds,
            frames: extraction.frames, normalize: extraction.normalize, inertia: extraction.inertia,
            coarseVerticesPerMode: core.objectInfo(coarse).verticesPerMode, mapping: {
              method: mapping.method, changed: mapping.changed, agreeHighest: mapping.agreeHighest,
              agreeFrequent: mapping.agreeFrequent}};
  });
  const coarseModes = core.loadObject(out + "/meshes/coarse_modes.om");
  core.deleteObject(high);
  high = core.loadObject(out + "/meshes/high_modes.om");

  // Stage 4: one multi-resolution mesh per delta.
  const multiNames = options.delta.map((delta) => "multires_d" + String(delta).replace(".", "p"));
  const multiFiles = [];
  for (const name of multiNames) multiFiles.push("meshes/" + name + ".om", "meshes/" + name + "_by_level.ply",
                                                 "meshes/" + name + "_by_mode.ply");
  const multiRecord = stages.run("refine-adaptive", multiFiles, () => {
    const meshes = [];
    options.delta.forEach((delta, k) => {
      const id = multirescloth.refineAdaptive(coarseModes, {delta: delta, maxLevel: options.levels + 1});
      const report = multirescloth.lastReport();
      const stem = out + "/meshes/" + multiNames[k];
      core.saveObject(id, stem + ".om");
      multirescloth.exportSurface(id, stem + "_by_level.ply", {colorBy: "level"});
      multirescloth.exportSurface(id, stem + "_by_mode.ply", {colorBy: "mode"});
      core.deleteObject(id);
      meshes.push({name: multiNames[k], delta: delta, vertices: report.vertices, faces: report.faces,
                   hangingNodes: report.hangingNodes, verticesPerLevel: report.verticesPerLevel,
                   facesPerLevel: report.facesPerLevel, passes: report.passes,
                   facesRefinedForBalance: report.facesRefinedForBalance, milliseconds: report.milliseconds});
    });
    return {meshes: meshes};
  });

  // Stage 5: the uniform level nearest (in ratio) the first multi-resolution mesh's vertex count.
  const target = multiRecord.meshes[0].vertices;
  const uniformRecord = stages.run("refine-equal", ["meshes/uniform_equal.om"], () => {
    // The coarse and high counts are known; only the levels between are refined to count them.
    const counts = [coarseInfo.vertices];
    const ids = [coarse];
    for (let level = 1; level < options.levels; ++level) {
      ids.push(multirescloth.refineUniform(coarse, level));
      counts.push(core.objectInfo(ids[level]).vertices);
    }
    counts.push(highRecord.vertices);
    let best = 0;
    counts.forEach((vertices, level) => {
      if (Math.abs(Math.log(vertices / target)) < Math.abs(Math.log(counts[best] / target))) best = level;
    });
    if (best < options.levels) core.saveObject(ids[best], out + "/meshes/uniform_equal.om");
    else core.saveObject(high, out + "/meshes/uniform_equal.om");
    for (let level = 1; level < ids.length; ++level) core.deleteObject(ids[level]);
    return {level: best, vertices: counts[best], target: target};
  });

  // Stage 6: every test motion on every model.
  const models = [{name: "coarse", file: "meshes/coarse_modes.om", vertices: coarseInfo.vertices}];
  multiRecord.meshes.forEach((mesh) => models.push({name: mesh.name, file: "meshes/" + mesh.name + ".om",
                                                    vertices: mesh.vertices}));
  models.push({name: "high", file: "meshes/high_modes.om", vertices: highRecord.vertices});
  // The nearest uniform level may be the coarse or the high-resolution mesh itself: no second run of it.
  if (uniformRecord.level > 0 && uniformRecord.level < options.levels)
    models.push({name: "uniform_L" + uniformRecord.level, file: "meshes/uniform_equal.om",
                 vertices: uniformRecord.vertices});
  stages.total = 6 + options.test.length * (models.length + 1);
  const runs = [];
  for (const test of options.test) {
    const motionName = baseName(test);
    models.forEach((model, k) => {
      const cache = "caches/" + model.name + "_" + motionName + ".pc2";
      const bodyCache = k === 0 ? "caches/body_" + motionName + ".pc2" : null;
      const files = [cache, cache.replace(/\.pc2$/, ".obj")];
      if (bodyCache) files.push(bodyCache, bodyCache.replace(/\.pc2$/, ".obj"));
      const record = stages.run("simulate-" + model.name + "-" + motionName, files, () => {
        const id = core.loadObject(out + "/" + model.file);
        const settings = onCharacter(options.testFrames, cache, bodyCache);
        settings.motion = motion(test);
        // Every model is the same garment, so its fit on this motion is
        // said once (each report still has it).
        if (k > 0) settings.fitWarning = false;
        if (options.objSequence) settings.objSequence = out + "/" + cache.replace(/\.pc2$/, "");
        const report = multirescloth.simulate(id, settings);
        core.deleteObject(id);
        mustFinish(model.name + " on " + motionName, report);
        return simulationNumbers(report);
      });
      runs.push({model: model.name, modelFile: model.file, motion: motionName, cache: cache,
                 bodyCache: "caches/body_" + motionName + ".pc2", numbers: record});
    });
  }

  // Stage 7: every model against the high-resolution result, at its material points.
  const detail = [];
  for (const test of options.test) {
    const motionName = baseName(test);
    const highRun = runs.find((run) => run.motion === motionName && run.model === "high");
    const others = runs.filter((run) => run.motion === motionName && run.model !== "high");
    const record = stages.run("compare-" + motionName, [], () => {
      const reference = core.loadObject(out + "/" + highRun.modelFile);
      const rows = others.map((run) => {
        const id = core.loadObject(out + "/" + run.modelFile);
        const c = multirescloth.compareResults(id, out + "/" + run.cache, reference, out + "/" + highRun.cache);
        core.deleteObject(id);
        if (c.cancelled) throw new Error("pipeline: the comparison of " + run.model + " was cancelled");
        return {model: run.model, vertices: run.numbers.vertices, meanRms: c.meanRms, meanP95: c.meanP95,
                maxDistance: c.maxDistance, wrinkleKept: c.wrinkleKept, wrinkleKeptRegion: c.wrinkleKeptRegion,
                wrinkleError: c.wrinkleError, wrinkleErrorRegion: c.wrinkleErrorRegion,
                regionMode: c.regionMode, regionPoints: c.regionPoints, rmsPerFrame: c.rmsPerFrame};
      });
      core.deleteObject(reference);
      return {motion: motionName, rows: rows};
    });
    for (const row of record.rows) detail.push(Object.assign({motion: motionName}, row));
  }

  // Stage 8: previews and plots.
  const previewRecord = stages.run("previews", previewFiles(options, models, multiNames), () =>
      renderPreviews(options, out, models, multiNames, runs, multiRecord, modesRecord, highRecord));

  // Stage 9: the report (always rewritten: it is cheap and reflects this run).
  const report = {
    mrcloth: "pipeline", options: resultOptions(options), garment: {file: options.garment, vertices: coarseInfo.vertices,
                                                                   faces: coarseInfo.faces, area: coarseInfo.area},
    table1Instance: {vertices: highRecord.vertices, frames: instanceRecord.frames, seconds: instanceRecord.seconds,
                     msPerFrame: instanceRecord.msPerFrame, maxStretch: instanceRecord.maxStretch,
                     maxTearOpening: instanceRecord.maxTearOpening, maxPenetration: instanceRecord.maxPenetration,
                     maxClothPenetration: instanceRecord.maxClothPenetration,
                     penetrationPinned: instanceRecord.penetrationPinned, stepRate: instanceRecord.stepRate, motion: baseName(options.instance)},
    table2Refinement: [{model: "high", vertices: highRecord.vertices, verticesPerLevel: highRecord.verticesPerLevel,
                        milliseconds: highRecord.milliseconds}].concat(
        multiRecord.meshes.map((mesh) => ({model: mesh.name, delta: mesh.delta, vertices: mesh.vertices,
                                           hangingNodes: mesh.hangingNodes, verticesPerLevel: mesh.verticesPerLevel,
                                           milliseconds: mesh.milliseconds}))),
    modes: modesRecord,
    uniformEqual: uniformRecord,
    table3: runs.map((run) => ({motion: run.motion, model: run.model, vertices: run.numbers.vertices,
                                dynamicsMs: run.numbers.msPerFrame.dynamics,
                                collisionMs: run.numbers.msPerFrame.collision, totalMs: run.numbers.msPerFrame.total,
                                maxStretch: run.numbers.maxStretch, maxTearOpening: run.numbers.maxTearOpening,
                                maxClothStretch: run.numbers.maxClothStretch, stretchPinned: run.numbers.stretchPinned,
                                maxPenetration: run.numbers.maxPenetration,
                                maxClothPenetration: run.numbers.maxClothPenetration,
                                penetrationPinned: run.numbers.penetrationPinned, maxFaceDepth: run.numbers.maxFaceDepth,
                                meanRounds: run.numbers.meanRounds, cache: run.cache, modelFile: run.modelFile})),
    // What every test run was given besides its motion and output (for
    // re-running one, as bench/distance_floor.js does).
    testSettings: characterSettings(options.testFrames),
    detail: detail,
    previews: previewRecord.images,
    stages: {ran: stages.ran, skipped: stages.skipped},
    seconds: (Date.now() - started) / 1000,
  };
  core.writeTextFile(out + "/report.json", JSON.stringify(report, null, 1) + "\n");
  core.writeTextFile(out + "/report.md", reportMarkdown(report));
  print("pipeline: " + runs.length + " runs of " + models.length + " models; report " + out + "/report.md (" +
        stages.ran.length + " stages run, " + stages.skipped.length + " resumed) in " +
        report.seconds.toFixed(1) + " s");
}

// --- Previews --------------------------------------------------------------------

function previewFiles(options, models, multiNames) {
  const files = ["previews/modes_coarse.png", "previews/modes_high.png", "previews/curvature_high.png",
                 "plots/time_per_frame.png", "plots/vertices_per_level.png", "plots/mode_histogram.png"];
  for (const name of multiNames) files.push("previews/levels_" + name + ".png");
  for (const test of options.test) files.push("previews/sheet_" + baseName(test) + ".png");
  return files;
}

function renderPreviews(options, out, models, multiNames, runs, multiRecord, modesRecord, highRecord) {
  const size = {width: options.size[0], height: options.size[1]};
  const cellSize = {width: Math.max(64, Math.round(size.width / 2)), height: Math.max(64, Math.round(size.height / 2))};
  core.makePath(out + "/previews/frames");
  const images = [];
  // The high-resolution mesh's wires would hide its colours: drawn without.
  const still = (file, meshFile, colorBy, camera, title, wireframe = true) => {
    const id = core.loadObject(out + "/" + meshFile);
    preview.render(id, out + "/" + file, Object.assign({colorBy: colorBy, camera: camera, title: title,
                                                        wireframe: wireframe}, size));
    core.deleteObject(id);
    images.push({file: file, title: title});
  };
  still("previews/modes_coarse.png", "meshes/coarse_modes.om", "mode", "three_quarter", "modes on the coarse garment");
  still("previews/modes_high.png", "meshes/high_modes.om", "mode", "three_quarter", "modes of the instance", false);
  still("previews/curvature_high.png", "meshes/high_modes.om", "curvature", "three_quarter",
        "mean bending curvature of the instance", false);
  multiNames.forEach((name) => still("previews/levels_" + name + ".png", "meshes/" + name + ".om", "level", "front",
                                     name + ": refinement levels"));

  // Per test motion: the models side by side at three frames, on the body.
  for (const test of options.test) {
    const motionName = baseName(test);
    const frames = [Math.floor(options.testFrames / 3), Math.floor(2 * options.testFrames / 3), options.testFrames - 1];
    const cells = [], captions = [];
    for (const run of runs.filter((r) => r.motion === motionName)) {
      const id = core.loadObject(out + "/" + run.modelFile);
      for (const frame of frames) {
        const file = out + "/previews/frames/" + run.model + "_" + motionName + "_f" + frame + ".png";
        preview.render(id, file, {cache: out + "/" + run.cache, frame: frame, colorBy: "level", camera: "front",
                                  width: cellSize.width, height: cellSize.height,
                                  body: {cache: out + "/" + run.bodyCache}});
        cells.push(file);
        captions.push(run.model + ", frame " + frame);
      }
      if (options.sequence && run.model === multiNames[0])
        preview.renderSequence(id, out + "/previews/frames/sequence_" + run.model + "_" + motionName, {
          cache: out + "/" + run.cache, colorBy: "level", camera: "front", width: cellSize.width,
          height: cellSize.height, fps: options.fps,
          animation: out + "/previews/sequence_" + run.model + "_" + motionName + ".gif",
          body: {cache: out + "/" + run.bodyCache}});
      core.deleteObject(id);
    }
    const sheet = "previews/sheet_" + motionName + ".png";
    preview.contactSheet(cells, out + "/" + sheet, {columns: frames.length, captions: captions,
                                                    title: motionName + ": models (rows) at frames " + frames.join(", ")});
    images.push({file: sheet, title: motionName + ": every model at three frames"});
  }

  // Plots.
  preview.lineChart(out + "/plots/time_per_frame.png", {
    title: "time per frame on " + baseName(options.test[0]), xLabel: "frame", yLabel: "ms (dynamics + collision)",
    series: runs.filter((run) => run.motion === baseName(options.test[0])).map((run) => ({
      name: run.model, x: run.numbers.perFrameMs.map((_, k) => k),
      y: run.numbers.perFrameMs.map((ms) => ms.dynamics + ms.collision)}))});
  const levelCount = Math.max(...multiRecord.meshes.map((mesh) => mesh.verticesPerLevel.length));
  const levelNames = [];
  for (let level = 1; level < levelCount; ++level) levelNames.push("level " + level);
  preview.barChart(out + "/plots/vertices_per_level.png", {
    title: "vertices per refinement level", yLabel: "vertices", categories: levelNames,
    series: multiRecord.meshes.map((mesh) => ({name: mesh.name, values: levelNames.map((_, k) =>
        mesh.verticesPerLevel[k + 1] === undefined ? 0 : mesh.verticesPerLevel[k + 1])}))});
  const modeNames = modesRecord.sizes.map((_, k) => "mode " + (k + 1));
  preview.barChart(out + "/plots/mode_histogram.png", {
    title: "vertices per deformation mode", yLabel: "vertices", categories: modeNames,
    series: [{name: "instance (" + highRecord.vertices + " vertices)", values: modesRecord.sizes},
             {name: "coarse garment", values: modeNames.map((_, k) => modesRecord.coarseVerticesPerMode[k + 1] || 0)}]});
  images.push({file: "plots/time_per_frame.png", title: "time per frame on " + baseName(options.test[0])},
              {file: "plots/vertices_per_level.png", title: "vertices per level"},
              {file: "plots/mode_histogram.png", title: "mode histogram"});
  return {images: images};
}

// --- The report ------------------------------------------------------------------

function reportMarkdown(report) {
  const lines = [];
  const fixed = (value, digits) => Number(value).toFixed(digits);
  lines.push("# mrcloth pipeline report", "");
  lines.push("Garment `" + report.garment.file.split("/").pop() + "`: " + report.garment.vertices + " vertices, " +
             report.garment.faces + " faces, " + fixed(report.garment.area, 3) + " m^2. Body: " +
             report.options.body + (report.options.makehuman ? " (MakeHuman)" : " (the mannequin)") +
             "; material " + report.options.material + (report.options.tNodeSag ? " (T-node sag read, tNodeSag)" : "") +
             (report.options.bendStiffness !== null && report.options.bendStiffness !== undefined
                  ? " with bend stiffness " + report.options.bendStiffness + " N/m" : "") +
             (report.options.bendModel && report.options.bendModel !== "distance"
                  ? " (" + report.options.bendModel + " bend springs)" : "") +
             (report.options.newtonCg ? "; Newton steps of " + report.options.newtonCg + " CG" : "") +
             (report.options.limiterAcceleration !== undefined && report.options.limiterAcceleration !== null
                  ? "; limiter acceleration " + report.options.limiterAcceleration : "") +
             "; " + report.options.fps + " fps" +
             (report.table1Instance.stepRate ? ", " + report.table1Instance.stepRate + " steps per second" : "") + ".", "");
  // The deepest vertex's penetration, and where it was a pinned one (it goes
  // where its pins take it, as a waist the thigh rises into in a squat, and
  // no step pushes it out) the cloth's own.
  const penetrationCell = (row) => fixed(1000 * row.maxPenetration, 2) + " mm" +
      (row.penetrationPinned && row.maxClothPenetration !== undefined
           ? " (pinned; cloth " + fixed(1000 * row.maxClothPenetration, 2) + " mm)" : "");
  lines.push("## Instance (Table 1)", "");
  const t1 = report.table1Instance;
  lines.push("| mesh | vertices | frames | motion | seconds | ms/frame | max stretch | tear opening | max penetration |",
             "|---|---:|---:|---|---:|---:|---:|---:|---:|",
             "| high (" + report.options.levels + " uniform levels) | " + t1.vertices + " | " + t1.frames + " | " +
                 t1.motion + " | " + fixed(t1.seconds, 1) + " | " + fixed(t1.msPerFrame.total, 1) + " | " +
                 fixed(100 * t1.maxStretch, 1) + " % | " + fixed(1000 * t1.maxTearOpening, 1) + " mm | " +
                 penetrationCell(t1) + " |", "");
  lines.push("## Refinement (Table 2)", "");
  lines.push("| mesh | delta | vertices | hanging nodes | vertices per level | ms |", "|---|---:|---:|---:|---|---:|");
  for (const row of report.table2Refinement)
    lines.push("| " + row.model + " | " + (row.delta === undefined ? "-" : row.delta) + " | " + row.vertices + " | " +
               (row.hangingNodes === undefined ? "-" : row.hangingNodes) + " | " +
               (row.verticesPerLevel ? row.verticesPerLevel.slice(1).join(" / ") : "-") + " | " +
               fixed(row.milliseconds, 1) + " |");
  const equal = report.uniformEqual;
  lines.push("", "The uniform comparison mesh is level " + equal.level + " (" + equal.vertices + " vertices), the " +
             "uniform level nearest the first multi-resolution mesh's " + equal.target + " vertices" +
             (equal.level === 0 ? ": the coarse mesh itself, so it is not run twice." :
              equal.level === report.options.levels ? ": the high-resolution mesh itself, so it is not run twice." : ".") +
             " Uniform refinement quadruples the faces per level, so a closer count needs another coarse mesh.", "");
  lines.push("## Modes", "");
  lines.push("k-means over " + report.modes.frames + " instance frames (" + report.modes.normalize +
             " normalisation): " + report.modes.sizes.map((size, k) => "mode " + (k + 1) + ": " + size + " vertices, mean " +
             fixed(report.modes.centroids[k][0], 2) + " 1/m").join("; ") + ". Mapped onto the coarse garment by " +
             report.modes.mapping.method + ".", "");
  lines.push("## Test motions (Table 3)", "");
  const motions = report.table3.map((row) => row.motion).filter((m, k, all) => all.indexOf(m) === k);
  // The largest stretch, and where it lay between pinned vertices (a
  // waistband the skin drives, which the solver cannot change) the cloth's own.
  const stretchCell = (row) => fixed(100 * row.maxStretch, 1) + " %" +
      (row.stretchPinned && row.maxClothStretch !== undefined ? " (pinned; cloth " + fixed(100 * row.maxClothStretch, 1) + " %)" : "");
  for (const motion of motions) {
    lines.push("### " + motion, "");
    lines.push("| model | vertices | dynamics ms/frame | collision ms/frame | total ms/frame | max stretch | tear opening | max penetration | faces sunk in |",
               "|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for (const row of report.table3.filter((r) => r.motion === motion))
      lines.push("| " + row.model + " | " + row.vertices + " | " + fixed(row.dynamicsMs, 2) + " | " +
                 fixed(row.collisionMs, 2) + " | " + fixed(row.totalMs, 2) + " | " + stretchCell(row) +
                 " | " + fixed(1000 * row.maxTearOpening, 1) + " mm | " + penetrationCell(row) + " | " +
                 (row.maxFaceDepth === undefined ? "-" : fixed(1000 * row.maxFaceDepth, 1) + " mm") + " |");
    lines.push("");
  }
  lines.push("## Detail against the high-resolution result", "");
  lines.push("Each model's surface evaluated at the high-resolution mesh's material points, every frame: mean " +
             "RMS and 95th-percentile distance, the largest distance, and the bending energy kept (squared " +
             "umbrella Laplacian on the high-resolution grid, summed over frames, relative to the " +
             "high-resolution result) over the whole garment and over the top-mode region.", "");
  for (const motion of motions) {
    lines.push("### " + motion, "");
    lines.push("| model | vertices | RMS | p95 | max | bending kept | in the top-mode region |",
               "|---|---:|---:|---:|---:|---:|---:|");
    const percent = (x) => x === null || x === undefined || !isFinite(x) ? "-" : fixed(100 * x, 1) + " %";
    for (const row of report.detail.filter((r) => r.motion === motion))
      lines.push("| " + row.model + " | " + row.vertices + " | " + fixed(1000 * row.meanRms, 2) + " mm | " +
                 fixed(1000 * row.meanP95, 2) + " mm | " + fixed(1000 * row.maxDistance, 1) + " mm | " +
                 percent(row.wrinkleKept) + " | " + percent(row.wrinkleKeptRegion) + " (mode " + row.regionMode +
                 ", " + row.regionPoints + " vertices) |");
    lines.push("");
  }
  lines.push("## Pictures", "");
  for (const image of report.previews) lines.push("### " + image.title, "", "![" + image.title + "](" + image.file + ")", "");
  lines.push("Caches (PC2 with their rest OBJ, and the body's) are in `caches/`; meshes (`.om` with every layer, " +
             "PLY coloured by level, mode or curvature) in `meshes/`. In Blender: import the rest OBJ, add a Mesh " +
             "Cache modifier, choose the PC2.", "");
  return lines.join("\n");
}
