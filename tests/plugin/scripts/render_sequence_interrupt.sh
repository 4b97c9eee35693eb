#!/bin/sh
# Ctrl-C during preview.renderSequence: the host exits with 130, a warning
# says how many images were written and kept (a sequence is frame files, each
# whole), every image it names is there, no more, and no temporary is left.
#
# render_sequence_interrupt.sh <mrcloth> <tests/data> <tmp folder>
set -u
. "$(dirname "$0")/wait_helpers.sh"
host=$1 data=$2 tmp=$3
rm -rf "$tmp" && mkdir -p "$tmp/frames" || exit 1
script="$tmp/long_sequence.js"
cat > "$script" <<'JS'
"use strict";
const [dataDir, tmpDir] = core.scriptArguments();
const grid = multirescloth.refineUniform(core.loadObject(dataDir + "/grid3x3.obj"), 1);
multirescloth.simulate(grid, {frames: 400, pins: [0, 1, 2, 3, 4], output: tmpDir + "/sheet.pc2"});
preview.renderSequence(grid, tmpDir + "/frames/f", {cache: tmpDir + "/sheet.pc2", width: 1600, height: 1200,
                                                   animation: tmpDir + "/never.gif"});
print("not reached: the sequence finished");
JS
env --default-signal=INT "$host" -b "$script" -- "$data" "$tmp" > "$tmp/stdout" 2> "$tmp/stderr" &
pid=$!
wait_for_line "$tmp/stderr" '^\[job\] renderSequence' "$pid" "the sequence"
sleep 1
interrupt_and_wait "$pid"
echo "--- stderr"; cat "$tmp/stderr"; echo "---"
failed=0
[ "$code" -eq 130 ] || { echo "exit code $code, expected 130"; failed=1; }
kept=$(sed -n 's/.*renderSequence: cancelled; stopped after \([0-9]*\) of 400 frames.*/\1/p' "$tmp/stderr")
[ -n "$kept" ] || { echo "no cancel warning naming the frames kept"; failed=1; kept=-1; }
written=$(ls "$tmp/frames" | grep -c '^f_[0-9]*\.png$')
[ "$written" -eq "$kept" ] || { echo "$written images written, the warning says $kept"; failed=1; }
others=$(ls "$tmp/frames" | grep -v '^f_[0-9]*\.png$')
[ -z "$others" ] || { echo "other files left: $others"; failed=1; }
[ -e "$tmp/never.gif" ] && { echo "an animation was made"; failed=1; }
grep -q 'not reached' "$tmp/stdout" && { echo "the script went on after Ctrl-C"; failed=1; }
[ "$failed" -eq 0 ] && echo "render sequence interrupt: ok"
exit "$failed"
