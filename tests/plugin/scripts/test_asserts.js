// The assertion helpers of the script tests, shared with
//   core.include("test_asserts.js");
// (core.include evaluates this file in the global scope: its functions and its
// `var`s become globals; a failed check throws an Error, which stops the test.)
"use strict";

/// How many expectThrows checks have passed (a `var`, so the including script sees it).
var checked = 0;

/// `actual` and `expected` have the same JSON text.
function expectEqual(actual, expected, what) {
  const got = JSON.stringify(actual), want = JSON.stringify(expected);
  if (got !== want) throw new Error(what + ": expected " + want + ", got " + got);
}

/// |actual - expected| <= tolerance (absolute).
function expectNear(actual, expected, tolerance, what) {
  if (!(Math.abs(actual - expected) <= tolerance))
    throw new Error(what + ": expected " + expected + " within " + tolerance + ", got " + actual);
}

/// |actual - expected| <= relative * |expected|.
function expectNearRelative(actual, expected, relative, what) {
  if (!(Math.abs(actual - expected) <= relative * Math.abs(expected)))
    throw new Error(what + ": expected " + expected + " within " + relative + " relative, got " + actual);
}

/// value <= limit (NaN fails).
function expectAtMost(value, limit, what) {
  if (!(value <= limit)) throw new Error(what + " " + value + " > " + limit);
}

/// value >= limit (NaN fails).
function expectAtLeast(value, limit, what) {
  if (!(value >= limit)) throw new Error(what + " " + value + " < " + limit);
}

/// The type of `value` is `type`: typeof, except "array" and "null".
function expectType(value, type, what) {
  const actual = Array.isArray(value) ? "array" : value === null ? "null" : typeof value;
  if (actual !== type) throw new Error(what + ": expected a " + type + ", got " + actual + " " + JSON.stringify(value));
}

/// call() throws an Error named `name` whose message contains every fragment; counts in `checked`.
function expectThrows(call, name, ...fragments) {
  let error = null;
  try {
    call();
  } catch (caught) {
    error = caught;
  }
  if (error === null) throw new Error("expected " + name + " containing " + JSON.stringify(fragments) + ", nothing thrown");
  if (!(error instanceof Error)) throw new Error("expected an Error object, got " + String(error));
  if (error.name !== name) throw new Error("expected a " + name + ", got " + error.name + ": " + error.message);
  for (const fragment of fragments)
    if (!error.message.includes(fragment))
      throw new Error("message '" + error.message + "' does not contain '" + fragment + "'");
  ++checked;
}

/// Ends the script as skipped (exit 77, which ctest reports as skipped) unless every path exists:
/// tests on ../shared/data run only where the shared data sits beside the checkout.
function skipUnlessFiles(paths) {
  for (const path of paths)
    if (!core.fileExists(path)) {
      print("SKIP: " + path + " not found (the shared data folder is not beside the checkout)");
      core.exitApplication(77);
    }
}

/// The shared MakeHuman inputs a character test needs: the garment file
/// (decimetres), CMU 07_06 and the body's files as a `body` option of type
/// `bodyType`. Skips the script (exit 77) unless all of them exist.
function sharedMakeHuman(sharedDir, garmentFile, bodyType) {
  const makehuman = sharedDir + "/bodies/makehuman";
  const inputs = {
    garment: sharedDir + "/garments/makehuman/" + garmentFile,
    clip: sharedDir + "/motions/cmu_mb/07_06.bvh",
    body: {type: bodyType, obj: makehuman + "/base.obj", skeleton: makehuman + "/rigs/cmu_mb.mhskel",
           weights: makehuman + "/rigs/default_weights.mhw"},
  };
  skipUnlessFiles([inputs.garment, inputs.clip, inputs.body.obj, inputs.body.skeleton, inputs.body.weights]);
  return inputs;
}
