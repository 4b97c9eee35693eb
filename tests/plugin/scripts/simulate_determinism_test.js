// The same simulation twice gives the same bytes: no hidden state between
// calls, no dependence on timing or the thread count. On a mesh with T-nodes, with colliders and
// pins; a different option gives a different cache (limiterMassExponent's,
// newtonCg's and bendModel's defaults given explicitly, the same). Arguments: <tests/data> <shared data> <tmp>.
"use strict";
const [dataDir, , tmpDir] = core.scriptArguments();

core.makePath(tmpDir);
const grid = core.loadObject(dataDir + "/grid3x3.obj");
multirescloth.setModes(grid, [5, 6, 9, 10], 3);
const refined = multirescloth.refineAdaptive(grid, {delta: 8, maxLevel: 3, balance: true});
if (!(core.objectInfo(refined).hangingNodes > 0)) throw new Error("expected T-nodes");

// The sheet hangs from its top row and swings onto a sphere and a floor.
const options = {
  frames: 15, substeps: 3, material: "silk", pins: [12, 13, 14, 15],
  gravity: [0, -9.81, -3],
  colliders: [{type: "sphere", center: [1.5, 1.5, -0.6], radius: 0.5, friction: 0.4},
              {type: "plane", point: [0, 0.2, 0], normal: [0, 1, 0]},
              {type: "capsule", a: [0, 1, -0.5], b: [3, 1, -0.5], radiusA: 0.1, radiusB: 0.3}],
};
const paths = [1, 2, 3].map(k => tmpDir + "/run" + k + ".pc2");
const reports = [];
for (const path of paths.slice(0, 2)) {
  options.output = path;
  reports.push(multirescloth.simulate(refined, options));
}
// An unrelated call in between must not matter either.
multirescloth.simulate(grid, {frames: 3, pins: "top"});
options.output = paths[2];
reports.push(multirescloth.simulate(refined, options));

// Threads resolve the vertices' collisions in parts: the same bytes with
// two, three, or one per core (0).
for (const threads of [2, 3, 0]) {
  options.output = tmpDir + "/run_threads" + threads + ".pc2";
  options.threads = threads;
  reports.push(multirescloth.simulate(refined, options));
  if (!core.filesEqual(paths[0], options.output)) throw new Error(threads + " threads wrote a different cache");
}
delete options.threads;

for (const report of reports) {
  if (report.nonFinite || report.frames !== 15) throw new Error("run failed: " + JSON.stringify(report));
  const measures = (r) => JSON.stringify([r.maxPenetration, r.maxDepth, r.deepest, r.maxStretch, r.maxSelfCrossings]);
  if (measures(report) !== measures(reports[0]))
    throw new Error("reports differ: " + measures(report) + " against " + measures(reports[0]));
}
if (!core.filesEqual(paths[0], paths[1])) throw new Error("two identical runs wrote different caches");
if (!core.filesEqual(paths[0], paths[2])) throw new Error("a run after another simulation wrote a different cache");

// Different options give different caches: the colliders matter, and so does
// the number of iterations.
const colliders = options.colliders;
options.output = tmpDir + "/run_no_colliders.pc2";
options.colliders = [];
multirescloth.simulate(refined, options);
if (core.filesEqual(paths[0], options.output)) throw new Error("the colliders did not change the motion");
options.output = tmpDir + "/run_iterations.pc2";
options.colliders = colliders;
options.iterations = 5;
multirescloth.simulate(refined, options);
if (core.filesEqual(paths[0], options.output)) throw new Error("more iterations wrote the same cache");
// One collision round a step: a different cache, and the report says one.
options.output = tmpDir + "/run_one_round.pc2";
options.iterations = 2;
options.collisionRounds = 1;
const oneRound = multirescloth.simulate(refined, options);
if (oneRound.meanRounds !== 1) throw new Error("collisionRounds 1 took " + oneRound.meanRounds + " rounds a step");
if (core.filesEqual(paths[0], options.output)) throw new Error("one collision round wrote the same cache");
// No limiter sweeps at all: a different cache again.
options.output = tmpDir + "/run_no_sweeps.pc2";
delete options.collisionRounds;
options.limiterSweeps = 0;
multirescloth.simulate(refined, options);
if (core.filesEqual(paths[0], options.output)) throw new Error("no limiter sweeps wrote the same cache");
// The limiter's mass exponent reaches the solver: its default (0.5) given
// explicitly writes the same bytes, mass-weighted projections (1) others.
delete options.limiterSweeps;
options.output = tmpDir + "/run_exponent_default.pc2";
options.limiterMassExponent = 0.5;
multirescloth.simulate(refined, options);
if (!core.filesEqual(paths[0], options.output)) throw new Error("limiterMassExponent 0.5 is not the default");
options.output = tmpDir + "/run_mass_weighted.pc2";
options.limiterMassExponent = 1;
multirescloth.simulate(refined, options);
if (core.filesEqual(paths[0], options.output)) throw new Error("mass-weighted limiter projections wrote the same cache");
delete options.limiterMassExponent;
// newtonCg and bendModel reach the solver: their defaults given explicitly
// write the same bytes, other values others.
for (const [key, same, other] of [["newtonCg", 0, 1], ["bendModel", "distance", "secondDifference"]]) {
  options.output = tmpDir + "/run_" + key + "_default.pc2";
  options[key] = same;
  multirescloth.simulate(refined, options);
  if (!core.filesEqual(paths[0], options.output)) throw new Error(key + " " + same + " is not the default");
  options.output = tmpDir + "/run_" + key + "_other.pc2";
  options[key] = other;
  const report = multirescloth.simulate(refined, options);
  if (report.nonFinite) throw new Error(key + " " + other + " went non-finite");
  if (core.filesEqual(paths[0], options.output)) throw new Error(key + " " + other + " wrote the same cache");
  delete options[key];
}
print("simulate determinism: ok");
