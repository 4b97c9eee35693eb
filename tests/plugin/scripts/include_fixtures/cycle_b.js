// Included by cycle_a.js: including cycle_a.js again, still being included, does nothing.
cycleLog.push("b includes a: " + core.include("include_fixtures/cycle_a.js"));
