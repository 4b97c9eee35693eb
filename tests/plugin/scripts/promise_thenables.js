// Thenables (objects with a `then`) resolve promises as the language says:
// one whose then throws rejects the promise (Qt 6.4 crashed the host with
// SIGSEGV: exit 139), a caught one is no error, and one left unhandled is
// reported as any rejection (it was silently dropped: exit 0). Checked by
// run_and_check.cmake: the output, the two reports, exit 1.
"use strict";
const throwing = {then() { throw new Error("then threw"); }};
const rejecting = {then(resolve, reject) { reject(new Error("thenable rejected")); }};
Promise.resolve(throwing).catch((e) => print("caught " + e.message));
Promise.resolve().then(() => throwing).catch((e) => print("caught from a callback: " + e.message));
new Promise((resolve) => resolve(rejecting)).catch((e) => print("caught " + e.message));
Promise.resolve({then(resolve) { resolve({then(again) { again(42); }}); }}).then((v) => print("nested " + v));
// A rejection after resolving with a thenable is ignored: the thenable decides.
new Promise((resolve, reject) => { resolve({then(r) { r("the thenable's"); }}); reject(new Error("ignored")); })
    .then((v) => print("kept " + v));
Promise.all([rejecting]).catch((e) => print("all: " + e.message));
Promise.resolve(throwing);                                // unhandled: reported at line 7
Promise.resolve().then(() => rejecting);                  // unhandled: reported at line 8
print("script done");
