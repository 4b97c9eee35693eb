#!/bin/sh
# Ctrl-C during multirescloth.simulate: the host exits with 130, the
# simulation reports "cancelled", and no cache (nor a temporary file) is left.
# With <resources>, the run is the embedded skirt on the embedded mannequin
# interrupted in a long pre-roll, which is one job with the motion's frames
# and cancels as they do.
#
# With SIGNAL=TERM in the environment, a batch system's SIGTERM instead:
# the same, exit code 143; with SIGNAL=HUP, a dropped ssh connection's
# SIGHUP: the same, exit code 129. With SIGNAL=IGNORED_INT, the host starts
# with SIGINT ignored (as a non-interactive shell starts a background job):
# a SIGINT is ignored, the run goes on, and a SIGTERM then stops it.
#
# simulate_interrupt.sh <mrcloth> <tests/data> <tmp folder> [<resources>]
set -u
. "$(dirname "$0")/wait_helpers.sh"
host=$1 data=$2 tmp=$3 resources=${4:-}
signal=${SIGNAL:-INT}
case "$signal" in
  INT) expected_code=130 ;;
  TERM) expected_code=143 ;;
  HUP) expected_code=129 ;;
  IGNORED_INT) expected_code=143 ;;
  *) echo "SIGNAL must be INT, TERM, HUP or IGNORED_INT, got $signal"; exit 1 ;;
esac
rm -rf "$tmp" && mkdir -p "$tmp" || exit 1
script="$tmp/long_simulation.js"
if [ -z "$resources" ]; then
  cat > "$script" <<'JS'
"use strict";
const [dataDir, tmpDir] = core.scriptArguments();
const grid = multirescloth.refineUniform(core.loadObject(dataDir + "/grid3x3.obj"), 2);
multirescloth.simulate(grid, {frames: 1000000, pins: [12, 13, 14, 15], output: tmpDir + "/never.pc2"});
print("not reached: the simulation finished");
JS
  cancelled='simulate: cancelled after [0-9]* of 1000000 frames'
  stopped='^\[job\] simulate: stopped at [0-9]*/1000000'
else
  cat > "$script" <<'JS'
"use strict";
const [resources, tmpDir] = core.scriptArguments();
const skirt = core.loadObject(resources + "/garments/default_skirt.obj");
multirescloth.simulate(skirt, {motion: {path: resources + "/characters/walk_instance.bvh", units: "m"},
                               body: {type: "capsules"}, place: "firstFrame", preroll: 60, frames: 10,
                               output: tmpDir + "/never.pc2"});
print("not reached: the simulation finished");
JS
  data=$resources
  cancelled='simulate: cancelled during the pre-roll, after [0-9]* of its 1800 frames'
  stopped='^\[job\] simulate: stopped at [0-9]*/1810'
fi
# This shell starts a background job with SIGINT ignored, which the host
# keeps; a terminal's Ctrl-C finds it at its default, as env sets it here.
if [ "$signal" = IGNORED_INT ]; then
  "$host" -b "$script" -- "$data" "$tmp" > "$tmp/stdout" 2> "$tmp/stderr" &
else
  env --default-signal=INT "$host" -b "$script" -- "$data" "$tmp" > "$tmp/stdout" 2> "$tmp/stderr" &
fi
pid=$!
# Wait until the simulation is running (its job line), at most 60 s.
wait_for_line "$tmp/stderr" '^\[job\] simulate: simulation of' "$pid" "the simulation"
sleep 0.5
if [ "$signal" = IGNORED_INT ]; then
  kill -INT "$pid"
  sleep 1
  kill -0 "$pid" 2>/dev/null || { echo "a SIGINT ignored on entry stopped the host"; }
  signal=TERM
fi
kill -"$signal" "$pid"
wait "$pid"
code=$?
echo "--- stderr"; cat "$tmp/stderr"; echo "--- stdout"; cat "$tmp/stdout"; echo "---"
failed=0
[ "$code" -eq "$expected_code" ] || { echo "exit code $code, expected $expected_code"; failed=1; }
grep -q "$cancelled" "$tmp/stderr" || { echo "no cancel warning"; failed=1; }
grep -q "$stopped" "$tmp/stderr" || { echo "no 'stopped at' job line"; failed=1; }
grep -q "interrupted (SIG$signal)" "$tmp/stderr" || { echo "no interrupt error"; failed=1; }
grep -q 'not reached' "$tmp/stdout" && { echo "the script went on after Ctrl-C"; failed=1; }
leftovers=$(ls "$tmp" | grep -v -e '^stdout$' -e '^stderr$' -e '^long_simulation\.js$')
[ -z "$leftovers" ] || { echo "files left behind: $leftovers"; failed=1; }
[ "$failed" -eq 0 ] && echo "interrupt: ok"
exit "$failed"
