// core.exitApplication inside a promise's callback ends the run with its
// code; the callbacks queued after it do not run.
"use strict";
Promise.resolve().then(() => { print("exiting"); core.exitApplication(4); });
Promise.resolve().then(() => Promise.resolve()).then(() => print("not reached"));
