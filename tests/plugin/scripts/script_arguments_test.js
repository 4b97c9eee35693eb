// Arguments after `--` reach the script unchanged, in order.
"use strict";
const args = core.scriptArguments();
const expected = ["one", "two words", "--not-an-option", "-b"];
if (JSON.stringify(args) !== JSON.stringify(expected))
  throw new Error("scriptArguments: expected " + JSON.stringify(expected) + ", got " + JSON.stringify(args));
print("script arguments: ok");
