// Promises' callbacks run once the script has run (QJSEngine queues them as
// events; a batch script runs no event loop of its own), in order, chained,
// and a handled rejection is no error: exit 0 (checked by run_and_check.cmake).
"use strict";
const order = [];
Promise.resolve(1)
    .then((v) => { order.push("then " + v); return v + 1; })
    .then((v) => { order.push("then " + v); return Promise.resolve(v + 1); })
    .then((v) => { order.push("then " + v); print(order.join(", ")); });
Promise.reject(new Error("handled")).catch((e) => print("caught " + e.message));
new Promise((resolve) => resolve("a value")).then((v) => print("resolved with " + v));
Promise.all([1, Promise.resolve(2)]).then((values) => print("all " + values.join("+")));
// Rejected and then handled later in the same script: not reported.
const later = Promise.reject(new Error("later"));
later.catch(() => print("caught later"));
// A rejection after resolving is ignored, as the language says.
new Promise((resolve, reject) => { resolve(1); reject(new Error("ignored")); });
print("script done");
