// The scripting API's descriptions (mrcloth --api) and the table of option
// bounds they print, which limits() also returns.
#include "multires_cloth_plugin.h"

#include "character_options.h"
#include "mesh_ops/mode_layer.h"
#include "mesh_ops/quad_refiner.h"
#include "option_limits.h"
#include "plugin/core/option_fields.h"
#include "solver/colliders.h"

namespace mrcloth {

namespace options {

QVariantMap limitsMap() {
  const auto range = [](double least, double most) { return QVariantList{least, most}; };
  return QVariantMap{{QStringLiteral("fps"), range(kLeastFps, kMostFps)},
                     {QStringLiteral("substeps"), range(1, kMostSubsteps)},
                     {QStringLiteral("stepsPerFrame"), range(1, kMostStepsPerFrame)},
                     {QStringLiteral("iterations"), range(1, kMostIterations)},
                     {QStringLiteral("newtonCg"), range(0, kMostNewtonCg)},
                     {QStringLiteral("limiterSweeps"), range(0, kMostLimiterSweeps)},
                     {QStringLiteral("collisionRounds"), range(1, kMostCollisionRounds)},
                     {QStringLiteral("threads"), range(0, kMostThreads)},
                     {QStringLiteral("preroll"), range(kShortestPreroll, kLongestPreroll)},
                     {QStringLiteral("motionSmoothing"), range(0, kLongestMotionSmoothing)},
                     {QStringLiteral("contactThickness"), range(0, kMostContactThickness)},
                     {QStringLiteral("selfContactThickness"), range(0, kMostSelfContactThickness)},
                     {QStringLiteral("mode"), range(0, kLargestMode)},
                     {QStringLiteral("clusters"), range(1, kLargestMode)},
                     {QStringLiteral("restarts"), range(1, kMostRestarts)},
                     {QStringLiteral("refinedFaces"), range(1, kMostFaces)},
                     {QStringLiteral("garmentSpan"), range(kGarmentSpanLow, kGarmentSpanHigh)}};
}

}  // namespace options

QList<SlotDescription> MultiresClothPlugin::slotDescriptions() const {
  const QString id_text = QStringLiteral("object id (from core.loadObject or a refinement)");
  QList<SlotDescription> descriptions{
      {QStringLiteral("refineUniform(int id, int levels) -> int"),
       QStringLiteral("Copies the object and splits every face `levels` times; returns the new object's id "
                      "(the input is untouched)."),
       {QStringLiteral("id"), QStringLiteral("levels")},
       {id_text, QStringLiteral("number of uniform 1-to-4 splits, >= 0 (the result may have @refinedFaces@ faces)")}},
      {QStringLiteral("setModes(int id, int[] vertexIds, int mode) -> int"),
       QStringLiteral("Sets the deformation mode of the given vertices; returns how many ids were given."),
       {QStringLiteral("id"), QStringLiteral("vertexIds"), QStringLiteral("mode")},
       {id_text, QStringLiteral("vertex indices in [0, vertices)"),
        QStringLiteral("mode to set, @mode@ (1 = least deformation, the default)")}},
      {QStringLiteral("paintModes(int id, object brush) -> int"),
       QStringLiteral("Sets the mode of the vertices a brush selects; returns how many. sphere: within radius of "
                      "center; geodesic: within radius along the mesh's edges from any seed; threshold: where a "
                      "per-vertex layer (getLayer) is >= threshold (<= with below)."),
       {QStringLiteral("id"), QStringLiteral("brush")},
       {id_text, QStringLiteral("{type: \"sphere\" | \"geodesic\" | \"threshold\" = \"sphere\", mode: int @mode@; "
                                "sphere: center [x, y, z] m, radius m (inclusive); geodesic: seeds int[], radius m; "
                                "threshold: layer (e.g. \"mean_curvature\"), threshold, below: bool = false}")}},
      {QStringLiteral("eraseModes(int id, int[] vertexIds = all) -> int"),
       QStringLiteral("Puts painted vertices back to the modes extractModes computed or mapModes mapped, which "
                      "refinement carries to new vertices (the default mode where none was); returns how many "
                      "changed."),
       {QStringLiteral("id"), QStringLiteral("vertexIds")},
       {id_text, QStringLiteral("vertex indices; omitted: every vertex")}},
      {QStringLiteral("getLayer(int id, string name) -> number[]"),
       QStringLiteral("A per-vertex layer, indexed by vertex: mode, computed_mode (what eraseModes goes back to: the default "
                      "mode before any analysis), mean_curvature and "
                      "curvature_deviation (1/m, after extractModes)."),
       {QStringLiteral("id"), QStringLiteral("name")},
       {id_text, QStringLiteral("layer name; an unknown one lists those the mesh has")}},
      {QStringLiteral("saveLayers(int id, string path)"),
       QStringLiteral("Writes every per-vertex layer as CSV (vertex, x, y, z, mode, computed_mode, then the "
                      "numeric layers), atomically. The .om format keeps the layers too."),
       {QStringLiteral("id"), QStringLiteral("path")},
       {id_text, QStringLiteral("a .csv path")}},
      {QStringLiteral("loadModes(int id, string path) -> int"),
       QStringLiteral("Sets modes from a CSV with vertex and mode columns (saveLayers' or any tool's); returns how "
                      "many rows. A malformed file changes nothing and names its line. Where the file has x, y, z "
                      "columns (saveLayers' do), rows farther than 0.1 mm from their vertex are warned of: modes of "
                      "another mesh, or of this one with its vertices renumbered, are set by vertex number all the "
                      "same."),
       {QStringLiteral("id"), QStringLiteral("path")},
       {id_text, QStringLiteral("a CSV path")}},
      {QStringLiteral("getModes(int id) -> int[]"),
       QStringLiteral("Returns the mode of every vertex, indexed by vertex."),
       {QStringLiteral("id")},
       {id_text}},
      {QStringLiteral("refineAdaptive(int id, object options = {}) -> int"),
       QStringLiteral("Copies the object and refines it where its modes ask for it (Algorithms 2 and 3); returns "
                      "the new object's id (the input is untouched). See lastReport()."),
       {QStringLiteral("id"), QStringLiteral("options")},
       {id_text, QStringLiteral("{delta: number = 8 (split a face when the R of its 4 corners sums to >= delta), "
                                "maxLevel: int >= 1 = 3 (coarse = 1), balance: bool = true (2:1 balance)}")}},
      {QStringLiteral("lastReport() -> object"),
       QStringLiteral("Report of the last refineUniform/refineAdaptive/simulate/recordInstance/mapModes/extractModes/"
                      "compareResults (its operation says which). Refinements: operation, source, "
                      "result, vertices, faces, hangingNodes, verticesPerLevel, facesPerLevel (element L = level "
                      "L), milliseconds; adaptive also facesRefinedPerPass, passes, facesRefinedForBalance, delta, "
                      "maxLevel, balance. The others: what they returned. {} before any of them."),
       {},
       {}},
      {QStringLiteral("exportSurface(int id, string path, object options = {})"),
       QStringLiteral("Writes the active surface to .obj or .ply (atomically), optionally with vertex colours; an "
                      "OBJ has the garment file's texture coordinates (vt) when it had them; with `cache`, the "
                      "surface at a frame of that simulation."),
       {QStringLiteral("id"), QStringLiteral("path"), QStringLiteral("options")},
       {id_text, QStringLiteral("output file; the extension picks the format"),
        QStringLiteral("{colorBy: \"level\" (the finest of each vertex's faces) | \"mode\" | \"curvature\" (mean "
                       "curvature after extractModes, viridis "
                       "from 0 to the largest) | \"none\" = \"none\", triangulate: bool = false, cache: PC2 of "
                       "this object (simulate's output) = none, frame: int >= 0 = 0 (of the cache)}")}},
      {QStringLiteral("limits() -> object"),
       QStringLiteral("The bounds of the numeric options, each [least, most], as the calls check them: fps, "
                      "substeps, stepsPerFrame (stepRate / fps on a character), iterations, newtonCg, "
                      "limiterSweeps, collisionRounds, threads, preroll (s; 0 is allowed too), motionSmoothing "
                      "(s), contactThickness (m: colliders and body), selfContactThickness (m), mode, clusters and restarts "
                      "(extractModes), refinedFaces "
                      "(faces a refinement may make), garmentSpan (m: the largest side of a garment worn on a "
                      "character). For checking a tool's own inputs before a run (the pipeline does)."),
       {},
       {}},
      {QStringLiteral("motionInfo(object motion) -> object"),
       QStringLiteral("Reads a BVH clip as a run on a character would (joints renamed, axes turned, units resolved) "
                      "and returns path, units (resolved: \"auto: cm\"), metresPerUnit, joints (names, End Sites "
                      "left out), frames (frame 0 included), frameTime (s), duration (s), legs (m, hip joint to ankle "
                      "in the rest pose, 0: no legs by CMU names), legsFactor (legs / an adult's 0.79 m), "
                      "jointsRenamed, axesTurned, axesUndecided (why axes \"auto\" could not tell which way the "
                      "clip stands, \"\" when it could), fastestLegSpeed {speed m/s, frame, joint} (the fastest "
                      "a joint of the legs moves between two frames from where a run starts: above 10 m/s, a glitch "
                      "or jitter that tears cloth; simulate warns), legJitter (m/s^2: the median over the frames "
                      "of the largest acceleration of a joint of the legs; clean clips 10-65, above 200 raw capture "
                      "jitter that tears cloth: simulate warns, motion.smoothing takes it out). A figure whose legs are not 0.4-2 times an adult's is refused "
                      "(InputError naming the units that would fit): its units look wrong. For checking clips "
                      "before a long batch."),
       {QStringLiteral("motion")},
       {QStringLiteral("simulate's `motion` option: a BVH path or {path, units: \"m\" | \"cmu\" | \"dm\" | "
                       "\"cm\" | \"mm\" | \"inch\" | \"auto\" = \"m\" or scale, skipFirst, start, joints, axes, "
                       "positions, smoothing}")}},
      {QStringLiteral("simulate(int id, object options = {}) -> object"),
       QStringLiteral("Simulates the object's cloth from rest (mass-spring model of paper section 6, implicit "
                      "steps) and returns a report: frames, steps, timeStep (s), precomputeMs, msPerFrame "
                      "{dynamics, collision, total, and their parts limiter (of dynamics), posing and firstRound (of "
                      "collision: posing moving bodies, each step's first collision round), and measure (not in total: "
                      "measuring each output frame for this report)}, maxStretch (strain), "
                      "maxClothStretch / maxPinnedStretch (the same over springs with a free end / between pinned "
                      "vertices), maxSelfCrossings (edge-triangle crossings of the cloth with itself, worst frame), "
                      "maxTearOpening (m: the largest excess over its rest length of an edge at least doubled, at "
                      "an output frame; 0: none doubled), meanRounds (strain-limiting and "
                      "collision rounds per step, 1 .. 8: the dynamics cost grows with them), maxPenetration (m: deepest "
                      "vertex inside a collider's surface + thickness at an output frame), maxDepth (m: deepest below "
                      "the surface itself), maxClothPenetration and maxClothDepth (m: the same over the vertices the solver moves), "
                      "maxPinnedDepth (m: over pinned vertices), maxPinYield (m: farthest a pin was moved off its target onto a "
                      "body's surface, see pinsYield), maxFaceDepth (m: deepest face centre below it; only vertices collide, so "
                      "large faces on a curved body sink in between their corners), deepest {vertex, frame, pinned} (where "
                      "maxPenetration was met; -1: never; pinned: a pinned vertex), "
                      "mostStretched {vertices: [i, j], frame} (the spring with maxStretch), initialPenetration (m: the cloth's at the start, pins not counted), nonFinite, cancelled, warnings (every warning the call logged), "
                      "output, vertices, freeVertices, pinnedVertices, hangingVertices, springs {stretch, shear, "
                      "bend}, perFrameMs [{dynamics, collision}], objFiles, resultId (with updateObject). The "
                      "object is untouched. Files appear only when the run completes (not on Ctrl-C or NaN). "
                      "With `motion` the garment is worn by a character: its waist follows the pelvis (Hips), a "
                      "body collides, a pre-roll (not recorded) blends the pose the garment was modelled on (the T-pose; "
                      "MakeHuman's A-pose with place \"makehuman\") into the clip's pose at `start`, "
                      "then `frames` frames of the motion are recorded; the report also has preroll {seconds, "
                      "frames, steps, msPerFrame, maxStretch, maxPenetration, maxDepth, initialPenetration, nonFinite}, "
                      "maxWaistError (m), fit (a tube garment's girth against the moving body's, level by level: "
                      "largestDemand, levels, stretchLimit), garmentCleared {vertices, largestMove} (skinned mesh: "
                      "vertices moved out of the body before the run), body, capsules or bodyVertices, motion (path), "
                      "motionUnits, motionStart, "
                      "motionDuration (s), skipFirst, place, placement [dx, dy, dz] (m), stepRate, legBridges, capsulesShrunk (capsules the garment started inside, shrunk to clear it), waistFollows, waistSmoothing (m, 0 when the waist follows the pelvis), "
                      "handMittens (mesh body: capsules standing in for its hands, 0: its own hands), "
                      "armsOpened {maxDegrees, steps, clearance (m; false when armClearance is)}, jointsRenamed {name in the file: CMU name} "
                      "(motion.joints), axesTurned (motion.axes: \"\" or e.g. \"x = x, y = z, z = -y\"). The rest pose is "
                      "the clip's T-pose moved to where the root is at `start`, so the pre-roll moves the joints, "
                      "not the character (a clip not facing +Z at `start` is turned to its heading during the "
                      "pre-roll); the cache is in the clip's coordinates once its axes are turned "
                      "(axesTurned: Y up), in metres."),
       {QStringLiteral("id"), QStringLiteral("options")},
       {id_text,
        QStringLiteral(
            "{frames: int >= 1 = 60, fps: @fps@ = 30, substeps: int @substeps@ = 4 (steps "
            "per frame), iterations: int @iterations@ = 2 (per step), newtonCg: int @newtonCg@ = 0 (k: each iteration a Newton step solved by k "
            "preconditioned conjugate-gradient iterations, less damped; 0: the plain iteration), limiterSweeps: int @limiterSweeps@ = 6 (strain-limiting sweeps per round), "
            "limiterAcceleration: \"auto\" | number in [0, 1) = \"auto\" (Chebyshev acceleration of those sweeps, a spectral radius "
            "estimate; a number fixes it, 0: plain Gauss-Seidel sweeps; \"auto\": 0.97 or, if larger and the cloth is not near rest, "
            "cos^2(pi / (n + 1)) for the garment's longest chain of n springs from a pin, 0.9935 for a skirt of 19 rows "
            "refined once, so refined garments stretch less (README); the report's limiterAcceleration is the "
            "chain's), "
            "limiterMassExponent: number in [0, 1] = 0.5 (the limiter moves a vertex in proportion to "
            "mass^-exponent; 1: mass-weighted, 0: equal), "
            "tNodeSag: bool = false (experimental: the limiter reads a spring from a T-node into the finer side from "
            "where the fine row beside it would put the T-node, not from the coarse edge's chord), "
            "pinsYield: bool = true (a pin whose target lies below a body's surface is moved out onto it for the step, "
            "as a thigh pushes a waistband; false: pins exactly at their targets, inside a body or not), "
            "collisionRounds: int @collisionRounds@ = 8 (rounds of strain limiting and collision checks per step, at most), "
            "optionNames: {option: string} (how the run's warnings name these options, for a tool that takes them "
            "under names of its own, e.g. {stepRate: \"--step-rate\"}; \"\": one the tool does not offer, whose "
            "advice is left out), "
            "contactSlack: m >= 0 = 0.002 (how far the strain limiter may move a point along its contact plane "
            "before the point is checked against the body again), selfContact: false | thickness m @selfContactThickness@ | "
            "{thickness, neighbourhood: m in [0, 0.1] = 2 (thickness + 0.01)} = false (cloth-cloth contact: layers kept "
            "that far apart; cloth joined at rest within the neighbourhood along the sheet is one sheet, never in "
            "contact, so folds with less cloth than that between their layers are not held), threads: int @threads@ = 1 (threads resolving collisions; 0: one per "
            "core; the same result for any count), material: \"cotton\" | \"denim\" | \"silk\" = \"cotton\" or "
            "{preset, arealDensity (kg/m^2), stretchStiffness, shearStiffness, bendStiffness (N/m), damping "
            "(1/s), stretchLimit (strain)}, alpha: number = 0 and alphaBend: number = 2 (stiffness x "
            "2^(alpha (level - 1))), bendModel: \"distance\" | \"secondDifference\" = \"distance\" (experimental: "
            "bend springs on |xi - 2 xmiddle + xj|, quadratic in the curvature; give its bendStiffness, about a "
            "thirtieth of the distance springs'), gravity: [x, y, z] m/s^2 = [0, -9.81, 0], pins: vertex ids or a boundary "
            "loop \"top\" | \"bottom\" | \"loop:N\" (or an array mixing both) = none, colliders: [{type: "
            "\"plane\", point = [0, 0, 0], normal = [0, 1, 0]} | {type: \"sphere\", center, radius} | {type: "
            "\"capsule\", a, b, radius or radiusA and radiusB}, each with thickness m @contactThickness@ = 0.002 and friction = "
            "0.3], output: PC2 file (its folder must exist) = none, objSequence: OBJ file prefix "
            "(<prefix>_0000.obj ...; written when the run completes, its frames held until then; later frames an "
            "earlier, longer sequence of the prefix left are removed) = none, updateObject: bool = false (store the last frame as a new "
            "object)}; lengths in m; every numeric bound as limits() gives it. On a character (all of these need `motion`; `substeps` is refused): "
            "motion: BVH file or {path, units: \"m\" | \"cmu\" (0.056444 m, CMU files) | \"dm\" | \"cm\" | "
            "\"mm\" | \"inch\" | \"auto\" (those giving the figure an adult's legs) = \"m\" or scale: metres "
            "per unit (a figure whose legs are not within 1.5 times the MakeHuman body's, or 0.4-2 times an "
            "adult's 0.79 m, is refused: its units look wrong), skipFirst: bool = true (drop frame 0, "
            "CMU's added T-pose), start: s = 0, joints: \"auto\" | \"asIs\" | {name in the file: CMU name} = "
            "\"auto\" (the joints renamed onto the CMU MotionBuilder names the waist, rig and capsules read; auto "
            "knows the DAZ/Poser and Mixamo names; joint names in other options are the renamed ones), axes: \"auto\" | "
            "\"asIs\" = \"auto\" (a clip whose rest pose is not Y up with the figure's left along +X, e.g. Z up, is "
            "turned by multiples of 90 degrees to stand so, as the MakeHuman body stands; exact), positions: \"absolute\" | "
            "\"relative\" = \"absolute\" (position channels are the joint's translation, its OFFSET only where it "
            "rests, as Blender and MotionBuilder write them; or added to the OFFSET; a CMU clip reads alike either "
            "way), smoothing: s @motionSmoothing@ = 0 (every channel smoothed in time by a Gaussian of this standard "
            "deviation, a joint's three rotation channels as one rotation, the ends continued by point "
            "reflection; 0.01-0.02 takes raw capture "
            "jitter out, which tears cloth on the legs: a run warns of a jittery clip with the smoothing that "
            "would do)}, "
            "skipFirst (also at the top level), body: \"capsules\" "
            "(default, from the skeleton) | {type: \"capsules\" | \"mesh\" = \"capsules\", obj, skeleton, weights "
            "(MakeHuman base.obj, .mhskel, .mhw: required for \"mesh\"; for capsules, fit their radii to "
            "that body), units: \"m\" | \"dm\" | \"cm\" | \"mm\" | \"inch\" = \"dm\" (base.obj's units; MakeHuman "
            "exports decimetres; a body not 0.5-3 m tall is refused with the units that fit), thickness m @contactThickness@ = "
            "0.004, friction = 0.3, radii: {joint name: r or [head, tail]} (m, capsules "
            "only, 0 removes that joint's capsules), legBridges: \"auto\" (or true) | false | 0.5 .. 2 = \"auto\" (capsules "
            "between the legs down to that many bones below the hips, 1 = knees, 2 = ankles, so a skirt cannot "
            "fold in between the legs and be caught; auto: for a garment with two boundary loops, to the knees "
            "or, if it reaches below them, the ankles, otherwise none), waistFollows: \"auto\" | \"pelvis\" | \"skin\" = "
            "\"auto\" (the pinned waist moves rigidly with the pelvis, or skinned like the MakeHuman body under it, "
            "which bends above the pelvis; auto: skin when the MakeHuman files are given, else pelvis), waistSmoothing: "
            "metres >= 0 = 0.02 (a skinned waist's skin weights averaged over the pins within about that, so the "
            "band keeps its length where skinning stretches the skin under it; 0: each pin exactly as its skin), armClearance: "
            "\"auto\" (or true) | false | metres 0 .. 0.1 = \"auto\" (0.02: each pose's upper arms open outward by the smallest "
            "angle that keeps the forearms and hands that far from the hips and thighs, as retargeting does when a "
            "body is wider than the capture subject; cloth pinched between a hand and a hip is inside the body "
            "whatever it does; false: the clip's arms), handMittens: boolean = true (type \"mesh\": the hands leave "
            "the collision mesh, the wrists capped, and collide as one capsule each, fitted to the hand: cloth "
            "caught between fingers is dragged off with the hand and torn; the body cache and previews draw "
            "the mittens, as the cloth collides; false: the hands' own triangles)}, place: \"none\" (the garment is "
            "already on the rest pose, standing where the clip starts) | \"makehuman\" (modelled on base.obj, loaded with units \"dm\"; needs the "
            "body's files) | \"firstFrame\" (modelled on the clip's frame 0, as the embedded garments are) = "
            "\"none\" (with each, the rest pose and the garment on it are turned to face as the clip starts where "
            "that is more than 30 degrees from the rest pose's facing), waist: like pins = \"top\" (or give pins, "
            "not both), preroll: s 0 or @preroll@ = 1 (from the rest pose to the motion's first frame), stepRate: "
            "steps per second, fps x @stepsPerFrame@ = 120, bodyOutput: PC2 file = none (the body at every output frame, its rest "
            "OBJ beside it: drawn by previews, loaded beside the garment in a DCC tool), fitWarning: bool = true (log a "
            "warning when a tube garment is too narrow for the motion, when the body overlaps its pins' targets "
            "by more than 1 mm, or when the cloth starts inside the body; the report's fit, maxPinYield, "
            "maxPinnedDepth and preroll.initialPenetration have them either way). With "
            "output, the rest mesh "
            "is written beside the cache as <name>.obj (restMesh in the report)")}},
      {QStringLiteral("extractModes(int id, string cachePath, object options = {}) -> object"),
       QStringLiteral("Learns the deformation modes of a mesh from a recorded instance (paper section 4): per "
                      "vertex, the bending curvature (1/m) over the cache's frames, its mean and population "
                      "deviation, normalised and clustered with k-means; modes 1..clusters in order of mean "
                      "curvature are written to the mesh's mode layer. Returns (and lastReport() keeps) the "
                      "report: frames, firstFrame, vertices, clusters, normalize, seed, restarts, restartKept, "
                      "iterations, inertia (normalised units), sizes (element m - 1: mode m), centroids and "
                      "normalizedCentroids ([mean curvature, deviation] per mode, 1/m and normalised), offset and "
                      "scale (normalised = (feature - offset) / scale), maxMeanCurvature, milliseconds."),
       {QStringLiteral("id"), QStringLiteral("cachePath"), QStringLiteral("options")},
       {id_text, QStringLiteral("a PC2 cache of this mesh's vertices (recordInstance's output), metres"),
        QStringLiteral("{clusters: int @clusters@ = 3, normalize: \"minmax\" | \"zscore\" = \"minmax\", seed: int >= 0 "
                       "= 1, restarts: int @restarts@ = 8, skipFrames: int >= 0 = 0, maxFrames: int >= 1 = all}")}},
      {QStringLiteral("compareResults(int id, string cachePath, int referenceId, string referenceCachePath, object "
                      "options = {}) -> object"),
       QStringLiteral("Measures a model's recorded result against the high-resolution one, frame by frame, at the "
                      "reference mesh's material points (both meshes refined from the same coarse mesh): the "
                      "model's surface is evaluated there by bilinear interpolation in its active faces. Returns "
                      "frames, points, meanRms, meanP95 (means over frames of the per-frame RMS and 95th "
                      "percentile distance, m), maxDistance (m), rmsPerFrame, p95PerFrame, wrinkleKept (the "
                      "model's bending energy, the squared umbrella Laplacian on the reference's grid summed over "
                      "frames, over the reference's; null when the reference is flat) and wrinkleKeptRegion (the "
                      "same over the interior vertices of mode regionMode; a coarser model's kinks along its face "
                      "edges count as bending there), wrinkleError and wrinkleErrorRegion (the energy of the "
                      "Laplacian of model - reference over the reference's: 0 = every wrinkle reproduced in "
                      "place, 1 = none), regionMode, regionPoints, cancelled, milliseconds."),
       {QStringLiteral("id"), QStringLiteral("cachePath"), QStringLiteral("referenceId"), QStringLiteral("referenceCachePath"),
        QStringLiteral("options")},
       {id_text, QStringLiteral("the model's PC2 cache (all its vertices)"),
        QStringLiteral("the reference (high-resolution) mesh's object id"),
        QStringLiteral("the reference's PC2 cache, the same frames"),
        QStringLiteral("{regionMode: int >= 1 = the reference's highest mode, maxFrames: int >= 1 = all}")}},
      {QStringLiteral("mapModes(int refinedId, int coarseId, object options = {}) -> object"),
       QStringLiteral("Writes the modes of a refined mesh (e.g. after extractModes) onto the coarse mesh it was "
                      "refined from, as its modes and its computed modes (what eraseModes goes back to). index: "
                      "coarse vertex i takes refined vertex i's mode (the paper's rule); "
                      "highest / frequent: the highest / most frequent mode (ties: the higher) in its cell, the "
                      "refined vertices in the quarters of its coarse faces nearest to it. Returns operation, "
                      "source, result, method, vertices, changed, agreeHighest and agreeFrequent (coarse vertices "
                      "where the index rule equals the cell's highest / most frequent mode)."),
       {QStringLiteral("refinedId"), QStringLiteral("coarseId"), QStringLiteral("options")},
       {QStringLiteral("the refined mesh, at rest"), QStringLiteral("the coarse mesh it was refined from (changed)"),
        QStringLiteral("{method: \"index\" | \"highest\" | \"frequent\" = \"index\"}")}},
      {QStringLiteral("recordInstance(int id, object options) -> object"),
       QStringLiteral("Records the instance motion of the paper: simulate with `motion` (required) and `output` "
                      "(required, the PC2 cache), 200 frames by default, and also writes the rest mesh the cache "
                      "plays on (placed as the run placed it, every vertex in cache order) beside the cache: same "
                      "name, .obj; for Blender's Mesh Cache modifier import it keeping the vertex order. Returns "
                      "simulate's report plus restMesh (the OBJ path). Nothing is written unless the run "
                      "completes."),
       {QStringLiteral("id"), QStringLiteral("options")},
       {id_text, QStringLiteral("simulate's options with motion and output required and frames = 200")}},
  };
  return withLimits(std::move(descriptions), options::limitsMap());
}

}  // namespace mrcloth
