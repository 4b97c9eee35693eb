// Runs with no plugin loaded: core works, and a missing plugin is a ReferenceError.
"use strict";
print("resources: " + core.resourcePath());
if (typeof multirescloth !== "undefined") throw new Error("multirescloth should not be loaded");
print("core only: ok");
