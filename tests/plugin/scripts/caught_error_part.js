// Included by caught_error_last.js: its last value is an Error made, not thrown.
new Error("made, not thrown");
