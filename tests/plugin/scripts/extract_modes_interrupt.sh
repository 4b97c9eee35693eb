#!/bin/sh
# Ctrl-C during multirescloth.extractModes' clustering: k-means restarts
# are the job's steps, so the host stops within a restart or so and exits
# 130 (it once ran every restart first: 34 s for 2,000 restarts of 50
# clusters on 175k vertices), saying the modes are unchanged.
#
# extract_modes_interrupt.sh <mrcloth> <tests/data> <tmp folder>
set -u
. "$(dirname "$0")/wait_helpers.sh"
host=$1 data=$2 tmp=$3
rm -rf "$tmp" && mkdir -p "$tmp" || exit 1
script="$tmp/long_clustering.js"
cat > "$script" <<'JS'
"use strict";
const [dataDir, tmpDir] = core.scriptArguments();
// A 49 x 49 sheet folding over a capsule: curvature enough for 50 clusters.
const sheet = multirescloth.refineUniform(core.loadObject(dataDir + "/grid3x3.obj"), 4);
multirescloth.simulate(sheet, {
  frames: 8, substeps: 2, material: "silk", pins: "top", gravity: [0, -9.81, -4], output: tmpDir + "/fold.pc2",
  colliders: [{type: "capsule", a: [-1, 1.5, -0.4], b: [4, 1.5, -0.4], radiusA: 0.25, radiusB: 0.25}],
});
multirescloth.extractModes(sheet, tmpDir + "/fold.pc2", {clusters: 50, restarts: 10000});
print("not reached: the clustering finished");
JS
env --default-signal=INT "$host" -b "$script" -- "$data" "$tmp" > "$tmp/stdout" 2> "$tmp/stderr" &
pid=$!
# Wait until the clustering is running (its job line), at most 60 s.
wait_for_line "$tmp/stderr" '^\[job\] extractModes: k-means of 50 clusters, 10000 restarts' "$pid" "the clustering"
sleep 0.5
interrupt_and_wait "$pid"
echo "--- stderr"; cat "$tmp/stderr"; echo "--- stdout"; cat "$tmp/stdout"; echo "---"
failed=0
[ "$code" -eq 130 ] || { echo "exit code $code, expected 130"; failed=1; }
# Generous for a loaded machine: it took 34 s before the restarts were the job's steps.
[ "$elapsed_ms" -le 5000 ] || { echo "the host took $elapsed_ms ms to stop, expected at most 5000"; failed=1; }
grep -q '^\[job\] extractModes: stopped at [0-9]*/10000' "$tmp/stderr" || { echo "no 'stopped at' job line"; failed=1; }
grep -q '^\[warn\] extractModes: cancelled during clustering, after [0-9]* of 10000 restarts; the modes are unchanged' "$tmp/stderr" || { echo "no cancel warning"; failed=1; }
grep -q 'interrupted (SIGINT)' "$tmp/stderr" || { echo "no interrupt error"; failed=1; }
grep -q 'not reached' "$tmp/stdout" && { echo "the script went on after Ctrl-C"; failed=1; }
[ "$failed" -eq 0 ] && echo "extract modes interrupt: ok ($elapsed_ms ms)"
exit "$failed"
