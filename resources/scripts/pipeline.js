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

// --- Options -----------------------------------------------------------------

function pipelineError(message, name = "ArgumentError") {
  const error = new Error("pipeline: " + message);
  error.name = name;
  return error;
}

const DEFAULTS = {
  garment: resources + "/garments/default_skirt.obj", units: null, makehuman: "", makehumanUnits: "dm",
  body: "capsules", place: null,
  instance: resources + "/characters/walk_instance.bvh",
  test: [resources + "/characters/walk_new.bvh", resources + "/characters/squat.bvh"], motionUnits: "m",
  motionPositions: "absolute", motionSmoothing: 0, jointMap: "",
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
  "--garment": "garment", "--units": "units", "--makehuman": "makehuman", "--makehuman-units": "makehumanUnits",
  "--body": "body", "--place": "place",
  "--instance": "instance", "--test": "test", "--motion-units": "motionUnits", "--levels": "levels",
  "--motion-positions": "motionPositions", "--motion-smoothing": "motionSmoothing", "--joint-map": "jointMap",
  "--modes": "modes", "--delta": "delta", "--map-modes": "mapModes", "--material": "material", "--fps": "fps",
  "--instance-frames": "instanceFrames", "--test-frames": "testFrames", "--preroll": "preroll", "--out": "out",
  "--threads": "threads", "--step-rate": "stepRate", "--newton-cg": "newtonCg", "--bend-model": "bendModel",
  "--bend-stiffness": "bendStiffness", "--waist-smoothing": "waistSmoothing",
  "--limiter-acceleration": "limiterAcceleration",
  "--size": "size",
};
const HOST_FLAGS = ["-q", "--quiet"];  // mrcloth's own, taken before the script sees its arguments
const UNITS = ["m", "dm", "cm", "mm", "inch"];
const MOST_INTEGER = 2147483647;  // 2^31 - 1: an integer option of the API
// The bounds of the values the API takes, as its calls check them
// (multirescloth.limits() and preview.limits(): [least, most] each), and the
// pipeline's own. Read when the first flag needs one: --help works without
// the plugins.
const apiLimits = {};  // plugin's script name -> its limits()
function limits(name, plugin = "multirescloth") {
  checkPlugins();
  if (!(plugin in apiLimits)) apiLimits[plugin] = (plugin === "preview" ? preview : multirescloth).limits();
  return apiLimits[plugin][name];
}
const limit = (name) => limits(name)[1];
const previewLimits = (name) => limits(name, "preview");
const LEAST_FPS = 1;             // the pipeline's own bounds: --fps
const MOST_WAIST_SMOOTHING = 1;  // and --waist-smoothing (m)
const LEAST_PREVIEW_SIDE = 64;   // and --size (pixels)
const PREVIEW_SUPERSAMPLE = 2;   // preview.render's default supersample, which the previews use
const DEFAULT_STEP_RATE = 120;  // simulate's stepRate when --step-rate is not given

/// The --help text; its bounds are the API's (multirescloth.limits()) where
/// the plugins are loaded, so they read as the options are checked.
function usage() {
  const api = typeof multirescloth !== "undefined" ? multirescloth.limits() : null;
  const range = (name) => api ? api[name].join("..") : "multirescloth.limits()." + name;
  const most = (name) => api ? String(api[name][1]) : "multirescloth.limits()." + name + "[1]";
  const previewApi = typeof preview !== "undefined" ? preview.limits() : null;
  const mostSide = previewApi ? String(previewApi.imageSide[1]) : "preview.limits().imageSide[1]";
  return [
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
    "  --makehuman-units U    base.obj's units: m, dm, cm, mm, inch [dm, as MakeHuman exports]",
    "  --body B               capsules | mesh (the skinned MakeHuman mesh) [capsules]",
    "  --place P              none | makehuman | firstFrame [makehuman with --makehuman, else firstFrame]",
    "  --waist-smoothing M    with --makehuman: metres (0.." + MOST_WAIST_SMOOTHING + ") along the waist over which its pins' skin weights",
    "                         are averaged, so the band keeps its length where skinning stretches the",
    "                         skin; 0: each pin as the skin under it (body.waistSmoothing; README) [0.02]",
    "  --instance FILE        BVH of the instance motion [embedded walk_instance.bvh]",
    "  --test FILE[,FILE...]  BVH test motions; repeatable [embedded walk_new.bvh,squat.bvh]",
    "  --motion-units U       m, cmu, dm, cm, mm, inch, or auto (per file, the units giving an adult's legs):",
    "                         the BVH files' units [m]",
    "  --motion-positions P   absolute | relative: the BVH position channels are each joint's translation",
    "                         (its OFFSET only where it rests; Blender, MotionBuilder) or are added to",
    "                         the OFFSET; CMU clips read alike either way [absolute]",
    "  --motion-smoothing S   seconds (" + range("motionSmoothing") + "): every clip smoothed in time by a Gaussian of this standard",
    "                         deviation; 0.01-0.02 takes raw capture jitter out (motion.smoothing; a run",
    "                         warns of a jittery clip with the smoothing that would do) [0: as recorded]",
    "  --joint-map FILE       JSON {\"name in the clip\": \"CMU name\", ...} for clips whose joints the",
    "                         automatic renaming (CMU, DAZ/Poser, Mixamo) does not know [automatic]",
    "Method:",
    "  --levels N             uniform refinements of the high-resolution mesh, >= 1, at most " + most("refinedFaces") + " faces [2]",
    "  --modes N              deformation modes (k-means clusters), " + range("clusters") + ", at most the high mesh's vertices [3]",
    "  --delta D[,D...]       adaptive thresholds, one multi-resolution mesh each, > 0 [5,7]",
    "  --map-modes M          index | highest | frequent: how the instance's modes reach the coarse garment",
    "                         (index: coarse vertex i takes high vertex i's, the paper's rule; highest /",
    "                         frequent: the highest / most frequent mode in its cell) [index]",
    "  --material M           cotton | denim | silk [cotton]",
    "  --t-node-sag           experimental: the limiter reads a spring from a T-node from where the fine",
    "                         row beside it would put the T-node (simulate's tNodeSag; README) [off]",
    "  --newton-cg K          each solve iteration a Newton step by K conjugate-gradient iterations, " + range("newtonCg") + ";",
    "                         less damped, costlier (simulate's newtonCg; README) [0: the plain iteration]",
    "  --bend-model M         distance | secondDifference: experimental bend springs quadratic in the",
    "                         curvature (simulate's bendModel; give --bend-stiffness) [distance, the paper's]",
    "  --bend-stiffness K     bend spring stiffness at level 1, N/m, >= 0 [the material's]",
    "  --limiter-acceleration A",
    "                         the strain limiter's Chebyshev estimate: a number in [0, 1) (0: plain sweeps),",
    "                         or auto (raised to the garment's chain's; simulate's limiterAcceleration;",
    "                         README, Collision cost) [simulate's default, auto]",
    "  --fps F                output frames per second, " + LEAST_FPS + ".." + most("fps") + " and at most --step-rate [30]",
    "  --step-rate HZ         simulation steps per second, --fps to " + most("stepsPerFrame") + " x --fps; fewer are cheaper and stretch more",
    "                         (README, Characters) [120, the CMU mocap rate]",
    "  --instance-frames N    recorded instance frames, >= 2 [200]",
    "  --test-frames N        frames per test motion, >= 1 [60]",
    "  --preroll S            seconds from the rest pose to each motion's start, 0 or " + range("preroll") + " [1]",
    "  --threads N            threads resolving collisions, " + range("threads") + " (0: one per core); the same results,",
    "                         but the reported times are then no longer one core's [1]",
    "Output:",
    "  --out DIR              output folder, created if missing [pipeline_out]",
    "  --resume               skip stages whose outputs are complete (same options and input files only;",
    "                         --threads and --size may differ: --size renders the previews again)",
    "  --size WxH             preview image size in pixels, " + LEAST_PREVIEW_SIDE + ".." + mostSide + " each [800x800]",
    "  --sequence             also render every frame of each test motion's first multi-resolution run",
    "                         (and an animated GIF of it when ImageMagick's convert is installed)",
    "  --obj-sequence         also write every simulated frame as OBJ (caches/<run>_0000.obj ...)",
    "  -q, --quiet            no progress (host option)",
    "  -h, --help             this text",
  ].join("\n");
}

function integerOption(name, text, least, most = MOST_INTEGER) {
  const value = Number(text);
  if (!/^[+]?\d+$/.test(text.trim()) || value < least || value > most)
    throw pipelineError("option " + name + ": expected an integer >= " + least +
                        (most < MOST_INTEGER || value > most ? " and <= " + most : "") + ", got \"" + text + "\"");
  return value;
}
function numberOption(name, text, least, strictly, most = Infinity) {
  const value = Number(text);
  if (text.trim() === "" || !isFinite(value) || (strictly ? value <= least : value < least) || value > most)
    throw pipelineError("option " + name + ": expected a number " + (strictly ? "> " : ">= ") + least +
                        (most < Infinity ? " and <= " + most : "") +
                        (text.includes(",") ? " (one number, decimals with a point: 5.5)" : "") + ", got \"" + text + "\"");
  return value;
}
function choiceOption(name, text, choices) {
  if (choices.indexOf(text) < 0)
    throw pipelineError("option " + name + ": expected one of " + choices.join(", ") + ", got \"" + text + "\"");
  return text;
}
/// A comma-separated list; an empty entry ("5,") is refused, naming it.
function listOption(name, text, what) {
  const parts = text.split(",");
  const empty = parts.indexOf("");
  if (empty >= 0)
    throw pipelineError("option " + name + ": entry " + (empty + 1) + " of \"" + text + "\" is empty; expected " + what +
                        " separated by commas");
  return parts;
}
/// The argument after `--name`: one that is itself an option (`--out --resume`) means the value was left out.
function optionValue(name, text) {
  const given = text.split("=")[0];
  if (FLAGS[given] !== undefined || VALUED[given] !== undefined || HOST_FLAGS.includes(given))
    throw pipelineError("option " + name + " needs a value, got the option " + given);
  return text;
}

/// Parses `--name value`, `--name=value` and flags; the last of a repeated
/// option wins except --test, which accumulates.
function parseOptions(args) {
  const options = Object.assign({}, DEFAULTS);
  let tests = null, waistGiven = false, makehumanUnitsGiven = false;
  for (let i = 0; i < args.length; ++i) {
    const argument = args[i];
    const equals = argument.startsWith("--") ? argument.indexOf("=") : -1;
    const name = equals < 0 ? argument : argument.slice(0, equals);
    if (FLAGS[name] !== undefined) {
      if (equals >= 0) throw pipelineError("option " + name + " takes no value");
      options[FLAGS[name]] = true;
      continue;
    }
    if (HOST_FLAGS.includes(name))
      throw pipelineError("option " + name + (equals >= 0 ? " takes no value" : " is mrcloth's, not the pipeline's: " +
                          "give it before -b (mrcloth -q -b pipeline.js -- ...)"));
    const key = VALUED[name];
    if (key === undefined)
      throw pipelineError((argument.startsWith("-") ? "unknown option " : "unexpected argument ") + "\"" + argument +
                          "\" (mrcloth pipeline --help lists the options)");
    let text;
    if (equals >= 0) text = argument.slice(equals + 1);
    else if (i + 1 < args.length) text = optionValue(name, args[++i]);
    else throw pipelineError("option " + name + " needs a value");
    switch (key) {
      case "levels": options.levels = integerOption(name, text, 1); break;
      case "modes": options.modes = integerOption(name, text, 1, limit("clusters")); break;
      case "instanceFrames": options.instanceFrames = integerOption(name, text, 2); break;
      case "testFrames": options.testFrames = integerOption(name, text, 1); break;
      case "threads": options.threads = integerOption(name, text, 0, limit("threads")); break;
      case "fps": options.fps = numberOption(name, text, LEAST_FPS, false, limit("fps")); break;
      case "preroll":
        options.preroll = numberOption(name, text, 0, false, limit("preroll"));
        // simulate's rule: 0 jumps to the first frame; shorter than 1 ms made steps too short to stay finite.
        if (options.preroll > 0 && options.preroll < limits("preroll")[0])
          throw pipelineError("option " + name + ": expected 0 or a number from " + limits("preroll").join(" to ") +
                              ", got \"" + text + "\"");
        break;
      case "stepRate": options.stepRate = numberOption(name, text, 0, true); break;
      case "newtonCg": options.newtonCg = integerOption(name, text, 0, limit("newtonCg")); break;
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
        options.waistSmoothing = numberOption(name, text, 0, false, MOST_WAIST_SMOOTHING);
        waistGiven = true;
        break;
      case "delta": {
        const values = listOption(name, text, "numbers > 0").map((part) => numberOption(name, part, 0, true));
        // Merging a repeated value made a decimal comma's "5,5" (meant: 5.5)
        // run delta 5 alone, without a word.
        const repeated = values.findIndex((value, k) => values.indexOf(value) !== k);
        if (repeated >= 0)
          throw pipelineError("option " + name + ": " + values[repeated] + " is given twice in \"" + text +
                              "\"; expected distinct numbers > 0 separated by commas, decimals with a point (5.5)");
        options.delta = values;
        break;
      }
      case "test":
        if (tests === null) tests = [];
        tests.push(...listOption(name, text, "file names"));
        break;
      case "units": options.units = choiceOption(name, text, UNITS); break;
      case "makehumanUnits":
        options.makehumanUnits = choiceOption(name, text, UNITS);
        makehumanUnitsGiven = true;
        break;
      case "motionUnits": options.motionUnits = choiceOption(name, text, ["m", "cmu", "dm", "cm", "mm", "inch", "auto"]); break;
      case "motionPositions": options.motionPositions = choiceOption(name, text, ["absolute", "relative"]); break;
      case "motionSmoothing": options.motionSmoothing = numberOption(name, text, 0, false, limit("motionSmoothing")); break;
      case "body": options.body = choiceOption(name, text, ["capsules", "mesh"]); break;
      case "place": options.place = choiceOption(name, text, ["none", "makehuman", "firstFrame"]); break;
      case "material": options.material = choiceOption(name, text, ["cotton", "denim", "silk"]); break;
      case "mapModes": options.mapModes = choiceOption(name, text, ["index", "highest", "frequent"]); break;
      case "size": {
        const match = /^(\d+)x(\d+)$/.exec(text);
        const [width, height] = match ? [Number(match[1]), Number(match[2])] : [NaN, NaN];
        const mostSide = previewLimits("imageSide")[1];
        if (!(width >= LEAST_PREVIEW_SIDE && height >= LEAST_PREVIEW_SIDE && width <= mostSide && height <= mostSide))
          throw pipelineError("option " + name + ": expected WIDTHxHEIGHT in pixels, " + LEAST_PREVIEW_SIDE + ".." +
                              mostSide + " each, got \"" + text + "\"");
        // The previews are drawn at preview.render's default samples a pixel,
        // which the renderer bounds (it would refuse them only after the
        // simulations).
        const mostPixels = Math.floor(previewLimits("samples")[1] / (PREVIEW_SUPERSAMPLE * PREVIEW_SUPERSAMPLE));
        if (width * height > mostPixels)
          throw pipelineError("option " + name + ": " + text + " is " + width * height + " pixels; expected at most " +
                              mostPixels + " (for instance " + Math.floor(Math.sqrt(mostPixels)) + "x" +
                              Math.floor(Math.sqrt(mostPixels)) + " or " + mostSide + "x" +
                              Math.floor(mostPixels / mostSide) + ")");
        options.size = [width, height];
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
  checkRates(options);
  if (options.jointMap) options.joints = readJointMap(options.jointMap);
  // The dm default is MakeHuman's, for a garment exported with the body;
  // the embedded skirt is the mannequin's, in metres, and not placed for it.
  if (options.makehuman && options.garment === DEFAULTS.garment && options.units === null)
    throw pipelineError("option --makehuman needs --garment FILE, a garment modelled on the MakeHuman body (read " +
                        "in dm, as MakeHuman exports); the embedded default skirt is made for the mannequin (give " +
                        "--units m --place firstFrame to put it on the MakeHuman body anyway)");
  if (options.units === null) options.units = options.makehuman ? "dm" : "m";
  if (options.place === null) options.place = options.makehuman ? "makehuman" : "firstFrame";
  if (options.body === "mesh" && !options.makehuman)
    throw pipelineError("option --body mesh needs --makehuman DIR (the skinned MakeHuman body)");
  if (makehumanUnitsGiven && !options.makehuman)
    throw pipelineError("option --makehuman-units needs --makehuman DIR (the body whose file it reads)");
  if (waistGiven && !options.makehuman)
    throw pipelineError("option --waist-smoothing needs --makehuman DIR (the body whose skin the waist follows)");
  if (options.place === "makehuman" && !options.makehuman)
    throw pipelineError("option --place makehuman needs --makehuman DIR (the body the garment was modelled on)");
  return options;
}

/// Every output frame takes whole simulation steps: --fps at most the step
/// rate (simulate's default when --step-rate is not given), and at most
/// 1000 steps a frame, simulate's bound on its substeps.
function checkRates(options) {
  if (options.stepRate === null && options.fps > DEFAULT_STEP_RATE)
    throw pipelineError("option --fps: expected at most the step rate, " + DEFAULT_STEP_RATE + " steps per second by " +
                        "default, got " + options.fps + "; give --step-rate HZ (at least --fps) for more frames per second");
  if (options.stepRate !== null && options.stepRate < options.fps)
    throw pipelineError("option --step-rate: expected at least --fps (" + options.fps + " frames per second), got " +
                        options.stepRate);
  if (options.stepRate !== null && options.stepRate > limit("stepsPerFrame") * options.fps)
    throw pipelineError("option --step-rate: expected at most " + limit("stepsPerFrame") + " steps per frame (" +
                        limit("stepsPerFrame") * options.fps + " at --fps " + options.fps + "), got " + options.stepRate);
}

/// The clips' joint map read from its JSON file: an object of names to names.
function readJointMap(path) {
  if (!core.fileExists(path)) throw pipelineError("option --joint-map: no such file: " + path);
  if (!core.fileReadable(path)) throw pipelineError("option --joint-map: cannot read " + path);
  let map;
  try {
    map = core.parseJson(fileText(path), path);  // read once: the fingerprint reads it too
  } catch (error) {
    throw pipelineError("option --joint-map: " + error.message.replace(/^core\.parseJson: /, "") +
                        ", in a file that should hold a joint map {\"name in the clip\": \"CMU name\", ...}");
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
  if (options.motionSmoothing > 0) motion.smoothing = options.motionSmoothing;
  if (options.joints) {
    const names = jointsInFile(options, path);
    const own = {};
    for (const [from, to] of Object.entries(options.joints))
      if (names.includes(from)) own[from] = to;
    if (Object.keys(own).length > 0) motion.joints = own;
  }
  return motion;
}

/// Every input must exist and be readable before any work starts. Returns
/// each input file's fingerprint (recorded for --resume).
function checkInputs(options) {
  checkOutputFolder(options.out);
  const inputs = inputFiles(options);
  for (const [name, path] of inputs) {
    if (!core.fileExists(path)) throw pipelineError("option " + name + ": no such file: " + path);
    if (!core.fileReadable(path)) throw pipelineError("option " + name + ": cannot read " + path);
  }
  if (options.makehuman) checkMakehumanRig(options.makehuman);
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
  for (const [name, path] of clips) checkClip(options, name, path);
  return inputs.map(([name, path]) => fingerprint(name, path));
}

/// Every input file with the option that names it, each once.
function inputFiles(options) {
  const inputs = [["--garment", options.garment], ["--instance", options.instance]];
  for (const test of options.test) inputs.push(["--test", test]);
  if (options.makehuman)
    for (const file of makehumanFiles(options.makehuman)) inputs.push(["--makehuman", file]);
  if (options.jointMap) inputs.push(["--joint-map", options.jointMap]);
  return inputs.filter(([, path], k) => inputs.findIndex(([, other]) => other === path) === k);
}

/// A clip is read as its runs will read it, and must have the pelvis the waist follows.
function checkClip(options, name, path) {
  let info;
  try {
    info = multirescloth.motionInfo(motionOption(options, path));
  } catch (error) {
    const message = error.message.replace(/^multirescloth\.motionInfo: option 'motion': /, "");
    // A renaming that clashes is the map's mistake, not the clip's.
    if (options.jointMap && /joint renaming/.test(message))
      throw pipelineError("option --joint-map: " + options.jointMap + " on " + message, error.name);
    throw pipelineError("option " + name + ": " + message, error.name);
  }
  // The waist follows the pelvis: a clip without it fails only at its run.
  if (!info.joints.includes("Hips")) {
    const shown = info.joints.slice(0, 8).join(", ") + (info.joints.length > 8 ? ", ..." : "");
    throw pipelineError("option " + name + ": " + path + " has no joint 'Hips' (after renaming), which the pinned " +
                        "waist follows; its joints: " + shown + "; expected CMU, DAZ/Poser or Mixamo names, or " +
                        "give --joint-map FILE.json {\"its pelvis\": \"Hips\", ...}", "InputError");
  }
}

/// The output folder, or the nearest of its parents that exists, must be a folder.
function checkOutputFolder(out) {
  const parts = out.split("/");
  for (let k = parts.length; k > 0; --k) {
    const path = parts.slice(0, k).join("/");
    if (path === "" || !core.fileExists(path)) continue;
    if (isFile(path))
      throw pipelineError("option --out: " + path + " exists and is not a folder" +
                          (k === parts.length ? "" : " (the folder " + out + " would be in it)") +
                          "; expected a folder, or a path where one can be made");
    return;
  }
}

/// `path` (which `folder + "/"` starts) relative to `folder`.
function relativeTo(folder, path) {
  if (!path.startsWith(folder + "/")) throw new Error("pipeline: " + path + " is not inside " + folder);
  return path.slice(folder.length + 1);
}

function isFile(path) {
  try {
    core.fileSize(path);  // InputError for a folder
    return true;
  } catch (error) {
    return false;
  }
}

function makehumanFiles(folder) {
  return [folder + "/base.obj", folder + "/rigs/cmu_mb.mhskel", folder + "/rigs/default_weights.mhw"];
}

/// The rig files are JSON objects with the sections the skinned body reads:
/// a broken one is refused now, not when the instance is first posed. (No
/// API call reads the body without a run, so base.obj is checked there.)
function checkMakehumanRig(folder) {
  const [, skeleton, weights] = makehumanFiles(folder);
  checkJsonSections(skeleton, ["bones", "joints"], "a MakeHuman skeleton (.mhskel)");
  checkJsonSections(weights, ["weights"], "MakeHuman skin weights (.mhw)");
}

function checkJsonSections(path, sections, what) {
  let json;
  try {
    json = core.parseJson(fileText(path), path);
  } catch (error) {
    throw pipelineError("option --makehuman: " + error.message.replace(/^core\.parseJson: /, "") +
                        ", in a file that should hold " + what, "InputError");
  }
  for (const section of sections)
    if (json === null || typeof json !== "object" || json[section] === null || typeof json[section] !== "object" ||
        Array.isArray(json[section]))
      throw pipelineError("option --makehuman: " + path + " has no \"" + section + "\" object; expected " + what,
                          "InputError");
}

/// Input files' text, read once (for the checks and the fingerprints).
const fileTexts = {};
function fileText(path) {
  if (!(path in fileTexts)) fileTexts[path] = core.readTextFile(path);
  return fileTexts[path];
}

/// What --resume compares to tell an input changed in place: its size and
/// the SHA-256 of its bytes.
function fingerprint(name, path) {
  return {option: name, path: path, bytes: core.fileSize(path), sha256: core.fileHash(path)};
}

/// The hash runs recorded before the SHA-256 (no `sha256` in their
/// fingerprints): 32-bit FNV-1a over the text's UTF-16 code units, which
/// reads a binary file's bytes that are not UTF-8 alike (so for a binary
/// garment such a run can tell only its size).
function textHash(path) {
  const text = fileText(path);
  let hash = 0x811c9dc5 | 0;
  for (let k = 0; k < text.length; ++k) hash = Math.imul(hash ^ text.charCodeAt(k), 16777619);
  return (hash >>> 0).toString(16).padStart(8, "0");
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
  // Runs from before --step-rate still resume, and the default given is the default.
  if (copy.stepRate === null || copy.stepRate === DEFAULT_STEP_RATE) delete copy.stepRate;
  // Likewise runs from before the solve and bend options, at their defaults.
  if (copy.newtonCg === 0) delete copy.newtonCg;
  if (copy.bendModel === "distance") delete copy.bendModel;
  if (copy.bendStiffness === null) delete copy.bendStiffness;
  if (copy.limiterAcceleration === null || copy.limiterAcceleration === "auto") delete copy.limiterAcceleration;
  // Runs from before the clips' reading options, read as these defaults do.
  if (copy.motionPositions === "absolute") delete copy.motionPositions;
  if (copy.motionSmoothing === 0) delete copy.motionSmoothing;
  if (!copy.jointMap) {
    delete copy.jointMap;
    delete copy.joints;
  }
  if (!copy.makehuman) delete copy.waistSmoothing;  // no skin to follow: it decides nothing
  if (copy.makehumanUnits === "dm") delete copy.makehumanUnits;  // as runs from before the option read the body
  return copy;
}

/// Options that may differ in a resumed run: they change no result (--threads:
/// the same numbers, only the times), or only a stage that checks them itself
/// (--size: the previews are rendered again).
const RESUME_FREE = ["threads", "size"];

/// The command-line option that sets an options key ("instanceFrames": "--instance-frames").
function optionName(key) {
  if (key === "joints") return "--joint-map";  // the map's contents
  const names = Object.keys(VALUED).filter((name) => VALUED[name] === key)
                    .concat(Object.keys(FLAGS).filter((name) => FLAGS[name] === key));
  return names.length > 0 ? names[0] : key;
}

const RESUME_AGAIN = "; run without --resume to start a new run, or use another --out";

/// With --resume, before the folder is locked: it must hold a run's record.
function checkResumable(out) {
  if (!core.fileExists(out)) throw pipelineError("--resume: " + out + " does not exist" + RESUME_AGAIN);
  if (!core.fileExists(out + "/stages/options.json"))
    throw pipelineError("--resume: " + out + " holds no stages/options.json, the record of a pipeline run's options" +
                        RESUME_AGAIN);
}

/// With --resume, before anything is written: the folder's record of its run
/// (stages/options.json) must hold this run's options and input files.
/// Returns that run's id, which its stage records carry.
function resumedRun(options, inputs) {
  const out = options.out, path = out + "/stages/options.json";
  const again = RESUME_AGAIN;
  checkResumable(out);
  let before;
  try {
    before = JSON.parse(core.readTextFile(path));
  } catch (error) {
    throw pipelineError("--resume: " + path + " is unreadable (" + error.message + ")" + again);
  }
  if (before === null || typeof before !== "object" || Array.isArray(before))
    throw pipelineError("--resume: " + path + " holds no object of options" + again);
  if (before.solverRevision !== SOLVER_REVISION)
    throw pipelineError("--resume: " + out + " holds a run made with other solver defaults (revision " +
                        (before.solverRevision === undefined ? 1 : before.solverRevision) + "; this build's " +
                        SOLVER_REVISION + "), whose results would mix with new ones" + again);
  if (typeof before.run !== "string" || !Array.isArray(before.inputs))
    throw pipelineError("--resume: " + out + " holds a run of an earlier pipeline, which recorded no fingerprints of " +
                        "its input files" + again);
  const now = resultOptions(options);
  const keys = Object.keys(now).concat(Object.keys(before).filter((key) => !(key in now)))
                   .filter((key) => !["run", "inputs"].includes(key) && !RESUME_FREE.includes(key));
  // Each option named once, with the run's value and this command's.
  const shown = (value) => value === undefined ? "not given" : JSON.stringify(value);
  const differing = [];
  for (const key of keys.filter((key) => JSON.stringify(before[key]) !== JSON.stringify(now[key]))) {
    const name = optionName(key);
    if (differing.some((text) => text.startsWith(name + " "))) continue;
    differing.push(name + " " + shown(before[key]) + " there, " + shown(now[key]) + " now");
  }
  if (differing.length > 0)
    throw pipelineError("--resume: " + out + " holds a run with other options (" + differing.join("; ") + ")" + again);
  for (const input of inputs) checkInputUnchanged(out, before.inputs, input, again);
  return before.run;
}

/// An input file changed in place since the run began would mix its results with new ones.
function checkInputUnchanged(out, recorded, input, again) {
  const was = recorded.find((entry) => entry && entry.path === input.path);
  if (was && was.bytes === input.bytes &&
      (was.sha256 !== undefined ? was.sha256 === input.sha256 : was.hash === textHash(input.path)))
    return;
  const how = !was ? "it is not among the run's inputs"
              : was.bytes !== input.bytes ? "now " + input.bytes + " bytes, then " + was.bytes
                                          : "the same size, other contents";
  throw pipelineError("--resume: " + input.path + " (" + input.option + ") has changed since the run in " + out +
                      " began (" + how + "), so its results would mix with new ones" + again, "InputError");
}

/// One run at a time in a folder: a second one would mix its outputs and
/// stage records with the first's. The lock (stages/.lock) goes with the
/// process, also when it is killed; then the temporaries its writers left
/// in the run's folders are swept.
function lockOutput(out) {
  core.makePath(out + "/stages");
  const lock = core.lockFile(out + "/stages/.lock");
  if (!lock.locked)
    throw pipelineError("option --out: " + out + " is in use by another pipeline run (" +
                        (lock.pid > 0 ? lock.application + " process " + lock.pid + (lock.host ? " on " + lock.host : "")
                                      : "its lock file stages/.lock names no process yet: one starting now, or a " +
                                        "run killed while starting, whose lock is taken over after 3 s") +
                        "); wait for it to end, or use another --out", "OutputError");
  // Only the folders a run writes: a folder inside --out may be another run's --out.
  const removed = [];
  for (const folder of ["", "/stages", "/meshes", "/caches", "/previews", "/previews/frames", "/plots"])
    removed.push(...core.removeTemporaries(out + folder));
  if (removed.length > 0)
    core.log("pipeline: removed " + removed.length + " temporary file" + (removed.length > 1 ? "s" : "") +
             " an interrupted writer left (" + removed.slice(0, 3).join(", ") + (removed.length > 3 ? ", ..." : "") + ")");
}

/// A new run's id: its stage records carry it, so those an earlier run left
/// in the folder (with other options or inputs) are never taken for its own.
function newRunId() {
  return Date.now().toString(36) + "-" + Math.floor(Math.random() * 0x7fffffff).toString(36);
}

class Stages {
  constructor(out, options, inputs, run, total) {
    this.out = out;
    this.total = total;  // stages this run has, for the "[k/total]" in progress lines
    this.folder = out + "/stages";
    this.resume = options.resume;
    this.runId = run;
    this.skipped = [];
    this.ran = [];
    core.makePath(this.folder);
    const record = Object.assign(resultOptions(options), {inputs: inputs, run: run});
    core.writeTextFile(this.folder + "/options.json", JSON.stringify(record));
  }

  /// The stage's record if this run wrote it and every file in `outputs`
  /// exists, else null; a broken record is warned of and run again.
  recordPath(name) {
    return this.folder + "/" + name + ".json";
  }

  finished(name, outputs) {
    const path = this.recordPath(name);
    if (!core.fileExists(path)) return null;
    let record;
    try {
      record = JSON.parse(core.readTextFile(path));
    } catch (error) {
      core.warn("pipeline: " + path + " is unreadable (" + error.message + "); running " + name + " again");
      return null;
    }
    if (record === null || typeof record !== "object" || typeof record.run !== "string") {
      core.warn("pipeline: " + path + " is not a stage record (it has no run id); running " + name + " again");
      return null;
    }
    // Another run's record (an earlier one, with other options) is not this run's result.
    if (record.run !== this.runId || JSON.stringify(record.outputs) !== JSON.stringify(outputs)) return null;
    // The files named only once the stage ran (--obj-sequence's, --sequence's) are checked as its others.
    const extra = record.extraOutputs === undefined ? [] : record.extraOutputs;
    if (!Array.isArray(extra) || !extra.every((file) => typeof file === "string")) {
      core.warn("pipeline: " + path + " holds no list of the further files " + name + " wrote; running " + name + " again");
      return null;
    }
    const written = outputs.concat(extra);
    const missing = written.find((file) => !isFile(this.out + "/" + file));
    if (missing !== undefined) {
      core.warn("pipeline: " + this.out + "/" + missing + ", which " + name + " wrote, is gone; running " + name + " again");
      return null;
    }
    // Records from before the outputs' fingerprints: their files' presence.
    if (!("files" in record)) return record;
    const fingerprinted = Array.isArray(record.files) && record.files.length === written.length &&
                          record.files.every((entry, k) => entry !== null && typeof entry === "object" &&
                                                           entry.file === written[k] && typeof entry.bytes === "number" &&
                                                           typeof entry.sha256 === "string");
    if (!fingerprinted) {
      core.warn("pipeline: " + path + " does not hold a size and SHA-256 for each of its files; running " + name + " again");
      return null;
    }
    for (const {file, bytes, sha256} of record.files) {
      const output = this.out + "/" + file, now = core.fileSize(output);
      if (now === bytes && core.fileHash(output) === sha256) continue;
      core.warn("pipeline: " + output + " is not the file " + name + " wrote (" +
                (now !== bytes ? "now " + now + " bytes, then " + bytes : "the same size, other contents") +
                "); running " + name + " again");
      return null;
    }
    return record;
  }

  /// Runs `work` (which returns the stage's record) unless resuming finds
  /// its record and every file in `outputs` (relative to the output folder)
  /// as the stage wrote it, and `fits(record)` if given. Files whose names
  /// only the work knows (one per frame) it lists in the record's
  /// `extraOutputs` (relative too): resuming checks them the same way.
  run(name, outputs, work, fits = () => true) {
    const label = "pipeline [" + (this.ran.length + this.skipped.length + 1) + "/" + this.total + "] " + name;
    const earlier = this.resume ? this.finished(name, outputs) : null;
    if (earlier && fits(earlier)) {
      core.log(label + ": complete from an earlier run, skipped");
      this.skipped.push(name);
      return earlier;
    }
    core.log(label + " ...");
    // What the host says if the run is interrupted (it cannot ask later).
    pipelineStage = {label: label.replace(/^pipeline /, ""), complete: this.ran.length + this.skipped.length};
    const started = Date.now();
    const record = work();
    record.stageSeconds = (Date.now() - started) / 1000;
    record.outputs = outputs;
    // What resuming checks the files against: cut short, replaced or edited since.
    record.files = outputs.concat(record.extraOutputs || []).map((file) => ({
      file: file, bytes: core.fileSize(this.out + "/" + file), sha256: core.fileHash(this.out + "/" + file)}));
    record.run = this.runId;
    core.writeTextFile(this.recordPath(name), JSON.stringify(record, null, 1) + "\n");
    this.ran.push(name);
    pipelineStage.complete += 1;
    return record;
  }
}

// --- The run ---------------------------------------------------------------------

/// The stage running and how many are complete: the host reads this global
/// to say where an interrupted run stopped.
var pipelineStage = null;  // eslint-disable-line no-var

// Users of the command meet its errors as a command's: the message (which
// names the option, file or line at fault), not this script's stack. Errors
// of other kinds (a TypeError is a bug here) keep their stack.
const REPORTED_ERRORS = ["ArgumentError", "InputError", "OutputError", "Error"];
try {
  const options = parseOptions(core.scriptArguments());
  if (options.help) {
    print(usage());
  } else {
    checkPlugins();
    runPipeline(options, checkInputs(options));
  }
} catch (error) {
  if (!(error instanceof Error) || !REPORTED_ERRORS.includes(error.name)) throw error;
  console.error(error.name + ": " + error.message);
  core.exitApplication(1);
}

/// The plugins every stage calls: without them (mrcloth --plugins FOLDER
/// naming another folder) the first call would fail as a ReferenceError.
function checkPlugins() {
  const missing = [];
  if (typeof multirescloth === "undefined") missing.push([, "Multires Cloth"]);
  if (typeof preview === "undefined") missing.push([, "Preview"]);
  if (missing.length > 0)
    throw pipelineError("the " + missing.map(([, plugin]) => "'" + plugin + "'").join(" and ") + " plugin" +
                        (missing.length > 1 ? "s are" : " is") + " not loaded (mrcloth --plugins FOLDER must name " +
                        "the folder holding them; by default the build's)", "Error");
}

/// A garment in the wrong units (centimetres read as metres: a 54 m skirt)
/// is refused before any work, with the units that would fit: the span
/// multirescloth.simulate accepts on a character (kGarmentSpanLow/High).
function checkGarmentSize(options, info) {
  const [low, high] = limits("garmentSpan");
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

/// The coarse garment, read and checked (with what its size bounds: --levels
/// and --modes) before anything is written: a broken file stops the run here.
function loadGarment(options) {
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
  checkLevels(options, coarseInfo);
  const highVertices = highVertexCount(coarse, coarseInfo, options.levels);
  if (options.modes > highVertices)
    throw pipelineError("option --modes: expected at most the high-resolution mesh's " + highVertices + " vertices " +
                        "(--levels " + options.levels + "), which k-means clusters, got " + options.modes);
  return {coarse: coarse, coarseInfo: coarseInfo};
}

/// Uniform refinement makes four faces of each per level, at most
/// limit("refinedFaces") (refineUniform's bound).
function checkLevels(options, coarseInfo) {
  const faces = coarseInfo.faces * Math.pow(4, options.levels);
  if (faces <= limit("refinedFaces")) return;
  let most = 0;
  while (coarseInfo.faces * Math.pow(4, most + 1) <= limit("refinedFaces")) ++most;
  throw pipelineError("option --levels: " + options.levels + " uniform refinements of the garment's " +
                      coarseInfo.faces + " faces would make " + faces.toPrecision(3) + " faces, more than the " +
                      limit("refinedFaces").toExponential() + " refinement makes; expected at most " + most);
}

/// The high-resolution mesh's vertex count without making it: each uniform
/// level adds a vertex per edge and per face, splits every edge in two and
/// adds four per face; the coarse mesh's edges are counted by refining it once.
function highVertexCount(coarse, coarseInfo, levels) {
  const once = multirescloth.refineUniform(coarse, 1);
  const onceVertices = core.objectInfo(once).vertices;
  core.deleteObject(once);
  let [vertices, edges, faces] = [coarseInfo.vertices, onceVertices - coarseInfo.vertices - coarseInfo.faces,
                                  coarseInfo.faces];
  for (let level = 0; level < levels; ++level) [vertices, edges, faces] = [vertices + edges + faces, 2 * edges + 4 * faces, 4 * faces];
  return vertices;
}

function runPipeline(options, inputs) {
  const out = options.out;
  const {coarse, coarseInfo} = loadGarment(options);
  if (options.resume) checkResumable(out);
  lockOutput(out);
  const run = options.resume ? resumedRun(options, inputs) : newRunId();
  // The report is written last: one left from an earlier run must not stand
  // beside this run's outputs if it stops before.
  for (const file of ["report.md", "report.json"]) core.removeFile(out + "/" + file);
  for (const folder of ["meshes", "caches", "previews", "plots"]) core.makePath(out + "/" + folder);
  // refine-uniform, instance, modes, refine-adaptive, refine-equal, previews, and
  // per test motion one simulation per model (the equal-size uniform mesh
  // counted) and a comparison; corrected once the models are known.
  const stages = new Stages(out, options, inputs, run, 6 + options.test.length * (4 + options.delta.length));
  const started = Date.now();

  const makehuman = options.makehuman ? makehumanFiles(options.makehuman) : null;
  const body = makehuman ? {type: options.body, obj: makehuman[0], skeleton: makehuman[1], weights: makehuman[2],
                            units: options.makehumanUnits, waistSmoothing: options.waistSmoothing}
                         : options.body;
  const motion = (path) => motionOption(options, path);
  // What a run on the character is given besides its motion and files.
  const material = options.bendStiffness === null ? options.material
                                                   : {preset: options.material, bendStiffness: options.bendStiffness};
  const characterSettings = (frames) => Object.assign(
      {body: body, place: options.place, frames: frames, fps: options.fps, preroll: options.preroll,
       material: material, tNodeSag: options.tNodeSag, threads: options.threads,
       // The runs' warnings name this command's flags, not simulate's options.
       optionNames: {stepRate: "--step-rate", fps: "--fps", preroll: "--preroll", pinsYield: ""}},
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
    threads: options.threads,  // the times are this many threads' (a resumed run may have others)
    warnings: report.warnings,
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
    const extraction = extractModes(high, out + "/caches/instance_high.pc2", options.modes);
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
  // Counted with the equal-size uniform mesh at first; said where it drops out.
  const total = 6 + options.test.length * (models.length + 1);
  if (total !== stages.total)
    core.log("pipeline: " + total + " stages in all, not " + stages.total + ": the uniform level nearest the " +
             "multi-resolution mesh's vertex count is the " + (uniformRecord.level === 0 ? "coarse" : "high-resolution") +
             " mesh itself, which is not run twice");
  stages.total = total;
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
        const numbers = simulationNumbers(report);
        if (options.objSequence) numbers.extraOutputs = report.objFiles.map((file) => relativeTo(out, file));
        return numbers;
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
      renderPreviews(options, out, models, multiNames, runs, multiRecord, modesRecord, highRecord),
      (record) => JSON.stringify(record.size) === JSON.stringify(options.size));

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
    // Every run's warnings, as the runs logged them (none: an empty list).
    warnings: [{run: "instance on " + baseName(options.instance), warnings: instanceRecord.warnings || []}].concat(
        runs.map((run) => ({run: run.model + " on " + run.motion, warnings: run.numbers.warnings || []})))
        .filter((entry) => entry.warnings.length > 0),
    // What every test run was given besides its motion and output (for
    // re-running one, as bench/distance_floor.js does).
    testSettings: Object.assign(characterSettings(options.testFrames),
                                {threads: timedThreads(options, [instanceRecord].concat(runs.map((r) => r.numbers)))}),
    detail: detail,
    previews: previewRecord.images,
    stages: {ran: stages.ran, skipped: stages.skipped},
    seconds: (Date.now() - started) / 1000,
  };
  core.writeTextFile(out + "/report.json", JSON.stringify(report, null, 1) + "\n");
  core.writeTextFile(out + "/report.md", reportMarkdown(report));
  print("pipeline: " + runs.length + " runs of " + models.length + " models; report " + out + "/report.md (" +
        stages.ran.length + " stages run, " + stages.skipped.length + " resumed) in " +
        report.seconds.toFixed(1) + " s" +
        (report.warnings.length > 0 ? "; " + report.warnings.length + " of its " + (runs.length + 1) +
                                      " simulations warned (its Warnings section)" : ""));
}

/// The modes, k-means on the instance's curvature: too few distinct values
/// for --modes clusters can only show now, and is said as the option's fault.
function extractModes(high, cache, modes) {
  try {
    return multirescloth.extractModes(high, cache, {clusters: modes});
  } catch (error) {
    const few = /(\d+) clusters requested but only (\d+) distinct points/.exec(error.message);
    if (!few) throw error;
    throw pipelineError("option --modes: the instance's curvature takes only " + few[2] + " distinct values over the " +
                        "high-resolution mesh's vertices; expected at most " + few[2] + " modes, got " + modes);
  }
}

/// The threads the report's times were measured on: the run's, unless a
/// resumed run's stages took them with others (then one that is not 1, so
/// bench/paper_targets.js does not take them for one core's).
function timedThreads(options, records) {
  const used = records.map((record) => record.threads === undefined ? options.threads : record.threads);
  return used.every((threads) => threads === used[0]) ? used[0] : used.find((threads) => threads !== 1);
}

// --- Previews --------------------------------------------------------------------

function previewFiles(options, models, multiNames) {
  const files = ["previews/modes_coarse.png", "previews/modes_high.png", "previews/curvature_high.png",
                 "plots/time_per_frame.png", "plots/vertices_per_level.png", "plots/mode_histogram.png"];
  for (const name of multiNames) files.push("previews/levels_" + name + ".png");
  for (const test of options.test) files.push("previews/sheet_" + baseName(test) + ".png");
  return files;
}

/// A contact sheet's cell: half the preview's size, or smaller (the same
/// shape) where `rows` by `columns` of them would pass the sheet's bound, by
/// contact_sheet.h's layout (10 pixels around each cell, 22 below it for its
/// caption, 34 for the title).
function sheetCell(size, rows, columns) {
  const most = previewLimits("sheetSide")[1];
  const half = {width: Math.max(64, Math.round(size.width / 2)), height: Math.max(64, Math.round(size.height / 2))};
  const scale = Math.min(1, (Math.floor((most - 10) / columns) - 10) / half.width,
                         (Math.floor((most - 44) / rows) - 32) / half.height);
  return {width: Math.floor(half.width * scale), height: Math.floor(half.height * scale)};
}

function renderPreviews(options, out, models, multiNames, runs, multiRecord, modesRecord, highRecord) {
  const size = {width: options.size[0], height: options.size[1]};
  core.makePath(out + "/previews/frames");
  const images = [];
  const frameFiles = [];  // the cells and sequence frames: the record's extraOutputs
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
    // Three frames, fewer when the run is shorter (one frame shown once, not three times).
    const frames = [...new Set([Math.floor(options.testFrames / 3), Math.floor(2 * options.testFrames / 3),
                                options.testFrames - 1])];
    const cells = [], captions = [];
    const motionRuns = runs.filter((r) => r.motion === motionName);
    const cellSize = sheetCell(size, motionRuns.length, frames.length);
    for (const run of motionRuns) {
      const id = core.loadObject(out + "/" + run.modelFile);
      for (const frame of frames) {
        const file = out + "/previews/frames/" + run.model + "_" + motionName + "_f" + frame + ".png";
        preview.render(id, file, {cache: out + "/" + run.cache, frame: frame, colorBy: "level", camera: "front",
                                  width: cellSize.width, height: cellSize.height,
                                  body: {cache: out + "/" + run.bodyCache}});
        cells.push(file);
        captions.push(run.model + ", frame " + frame);
      }
      if (options.sequence && run.model === multiNames[0]) {
        const animation = out + "/previews/sequence_" + run.model + "_" + motionName + ".gif";
        frameFiles.push(...preview.renderSequence(id, out + "/previews/frames/sequence_" + run.model + "_" + motionName, {
          cache: out + "/" + run.cache, colorBy: "level", camera: "front", width: cellSize.width,
          height: cellSize.height, fps: options.fps, animation: animation, body: {cache: out + "/" + run.bodyCache}}));
        // Without an encoder it is not written (renderSequence warned).
        if (isFile(animation)) frameFiles.push(animation);
      }
      core.deleteObject(id);
    }
    frameFiles.push(...cells);
    const sheet = "previews/sheet_" + motionName + ".png";
    const atFrames = (frames.length === 1 ? "frame " : "frames ") + frames.join(", ");
    preview.contactSheet(cells, out + "/" + sheet, {columns: frames.length, captions: captions,
                                                    title: motionName + ": models (rows) at " + atFrames +
                                                           " (from 0: the cache's first sample is 0)"});
    images.push({file: sheet, title: motionName + ": every model at " + atFrames});
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
  return {images: images, size: options.size, extraOutputs: frameFiles.map((file) => relativeTo(out, file))};
}

// --- The report ------------------------------------------------------------------

/// Text from a file or motion name for a Markdown table cell, heading or
/// image alt text, read as the text it is: "|" would end the cell, "[" and
/// "]" the alt text, "<" start HTML (a "<!--" hid the rest of the report),
/// "*" and "`" emphasis and code, "_" emphasis where it starts or ends a
/// word (inside one, as in "walk_new", it is text), and a line break would
/// end the heading or the line.
function markdownText(text) {
  return String(text).replace(/[\r\n]+/g, " ").replace(/[\\|[\]<>*`]/g, "\\$&")
      .replace(/(^|[^A-Za-z0-9])_|_(?=$|[^A-Za-z0-9])/g, (match) => match.replace("_", "\\_"));
}
/// A relative path as a Markdown link target: each part percent-encoded, and
/// "(" and ")" too, which encodeURIComponent leaves. "walk 1.bvh"'s preview
/// was linked as "(previews/sheet_walk 1.png)", which does not render.
function markdownLinkTarget(path) {
  return path.split("/").map((part) => encodeURIComponent(part).replace(/[()]/g,
      (c) => "%" + c.charCodeAt(0).toString(16).toUpperCase())).join("/");
}

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
             (report.options.motionSmoothing ? "; clips smoothed in time by " + report.options.motionSmoothing + " s" : "") +
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
                 markdownText(t1.motion) + " | " + fixed(t1.seconds, 1) + " | " + fixed(t1.msPerFrame.total, 1) + " | " +
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
    lines.push("### " + markdownText(motion), "");
    lines.push("| model | vertices | dynamics ms/frame | collision ms/frame | total ms/frame | max stretch | tear opening | max penetration | faces sunk in |",
               "|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for (const row of report.table3.filter((r) => r.motion === motion))
      lines.push("| " + row.model + " | " + row.vertices + " | " + fixed(row.dynamicsMs, 2) + " | " +
                 fixed(row.collisionMs, 2) + " | " + fixed(row.totalMs, 2) + " | " + stretchCell(row) +
                 " | " + fixed(1000 * row.maxTearOpening, 1) + " mm | " + penetrationCell(row) + " | " +
                 (row.maxFaceDepth === undefined ? "-" : fixed(1000 * row.maxFaceDepth, 1) + " mm") + " |");
    lines.push("");
  }
  if (report.warnings.length > 0) {
    lines.push("## Warnings", "", "What the runs warned of (the same lines as on stderr):", "");
    for (const entry of report.warnings)
      for (const warning of entry.warnings) lines.push("- " + markdownText(entry.run) + ": " + markdownText(warning));
    lines.push("");
  }
  lines.push("## Detail against the high-resolution result", "");
  lines.push("Each model's surface evaluated at the high-resolution mesh's material points, every frame: mean " +
             "RMS and 95th-percentile distance, the largest distance, and the bending energy kept (squared " +
             "umbrella Laplacian on the high-resolution grid, summed over frames, relative to the " +
             "high-resolution result) over the whole garment and over the top-mode region.", "");
  for (const motion of motions) {
    lines.push("### " + markdownText(motion), "");
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
  for (const image of report.previews)
    lines.push("### " + markdownText(image.title), "",
               "![" + markdownText(image.title) + "](" + markdownLinkTarget(image.file) + ")", "");
  lines.push("Caches (PC2 with their rest OBJ, and the body's) are in `caches/`; meshes (`.om` with every layer, " +
             "PLY coloured by level, mode or curvature) in `meshes/`. In Blender: import the rest OBJ, add a Mesh " +
             "Cache modifier, choose the PC2.", "");
  return lines.join("\n");
}
