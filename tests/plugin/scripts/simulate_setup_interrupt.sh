#!/bin/sh
# Ctrl-C during a simulation's set-up (building the model, ordering and
# factorising its system: 3 s for the 148k vertices here before its first
# frame): the job has started and says it is setting up, the host stops
# before any frame (it once ran the whole set-up and a frame first) and
# exits 130, and no cache (nor a temporary file) is left.
#
# simulate_setup_interrupt.sh <mrcloth> <tests/data> <tmp folder>
set -u
. "$(dirname "$0")/wait_helpers.sh"
host=$1 data=$2 tmp=$3
rm -rf "$tmp" && mkdir -p "$tmp" || exit 1
script="$tmp/large_simulation.js"
cat > "$script" <<'JS'
"use strict";
const [dataDir, tmpDir] = core.scriptArguments();
const sheet = multirescloth.refineUniform(core.loadObject(dataDir + "/grid3x3.obj"), 7);  // 385 x 385 vertices
multirescloth.simulate(sheet, {frames: 1000, pins: "top", output: tmpDir + "/never.pc2"});
print("not reached: the simulation finished");
JS
env --default-signal=INT "$host" -b "$script" -- "$data" "$tmp" > "$tmp/stdout" 2> "$tmp/stderr" &
pid=$!
# Wait until the simulation's job has started (its first line), at most 60 s.
wait_for_line "$tmp/stderr" '^\[job\] simulate: simulation of .*; setting up first' "$pid" "the simulation"
sleep 0.3
interrupt_and_wait "$pid"
echo "--- stderr"; cat "$tmp/stderr"; echo "--- stdout"; cat "$tmp/stdout"; echo "---"
failed=0
[ "$code" -eq 130 ] || { echo "exit code $code, expected 130"; failed=1; }
# Generous: the longest phase (the bend pairs) takes 0.8 s here.
[ "$elapsed_ms" -le 5000 ] || { echo "the host took $elapsed_ms ms to stop, expected at most 5000"; failed=1; }
grep -q '^\[job\] simulate: stopped at 0/1000' "$tmp/stderr" || { echo "not stopped before the first frame"; failed=1; }
grep -q '^\[warn\] simulate: cancelled while setting up, before the first of 1000 frames; nothing was written' "$tmp/stderr" || { echo "no cancel warning"; failed=1; }
grep -q 'interrupted (SIGINT)' "$tmp/stderr" || { echo "no interrupt error"; failed=1; }
grep -q 'not reached' "$tmp/stdout" && { echo "the script went on after Ctrl-C"; failed=1; }
leftovers=$(ls -A "$tmp" | grep -v -e '^stdout$' -e '^stderr$' -e '^large_simulation\.js$')
[ -z "$leftovers" ] || { echo "files left behind: $leftovers"; failed=1; }
[ "$failed" -eq 0 ] && echo "simulate setup interrupt: ok ($elapsed_ms ms)"
exit "$failed"
