#!/bin/sh
# The pipeline end to end on a very small configuration: `mrcloth pipeline`
# writes every file its report names; `mrcloth -b pipeline.js` with the same
# options, on two threads, gives the same numbers; --resume runs nothing again and reports the
# same; Ctrl-C stops it with 130 and leaves only complete files, and a resume
# then finishes the run; bench/distance_floor.js reproduces its distances;
# bench/still_drape.js measures every model on the walk held still.
#
# pipeline_test.sh <mrcloth> <resources> <test scripts> <tmp folder>
set -u
host=$1 resources=$2 scripts=$3 tmp=$4
rm -rf "$tmp" && mkdir -p "$tmp" || exit 1
# Small: one uniform level, 8 instance frames, 5 frames of one test walk, short pre-roll.
small="--levels 1 --modes 2 --delta 6,8 --instance-frames 8 --test-frames 5 --preroll 0.2 --size 160x160
       --test $resources/characters/walk_new.bvh"
failed=0
fail() { echo "FAILED: $*"; failed=1; }

# 1. The command.
"$host" -q pipeline $small --out "$tmp/command" > "$tmp/command.out" 2> "$tmp/command.err"
code=$?
[ "$code" -eq 0 ] || { fail "pipeline exit code $code"; cat "$tmp/command.err"; }
[ -s "$tmp/command.err" ] && fail "--quiet printed on stderr: $(cat "$tmp/command.err")"
# Coarse, two multi-resolution meshes, high; the uniform level nearest 1395 vertices is the coarse mesh.
grep -q "^pipeline: 4 runs of 4 models" "$tmp/command.out" || fail "no summary line: $(cat "$tmp/command.out")"
grep -q '"warnings": \[\]' "$tmp/command/report.json" || fail "report.json: no empty warnings list"
grep -q "## Warnings" "$tmp/command/report.md" && fail "report.md: a Warnings section with nothing to warn of"

# 1b. Runs that warn (a pre-roll too short for the legs): each simulation's
# warnings in report.json and report.md, and counted in the summary line.
"$host" -q pipeline --levels 1 --instance-frames 2 --test-frames 1 --preroll 0.02 --size 64x64 \
  --test "$resources/characters/walk_new.bvh" --out "$tmp/warned" > "$tmp/warned.out" 2> "$tmp/warned.err" ||
  fail "warned run exit code $?"
grep -q "; 5 of its 5 simulations warned (its Warnings section)" "$tmp/warned.out" ||
  fail "warned run's summary: $(cat "$tmp/warned.out")"
grep -q "^- multires_d5 on walk_new: simulate: the pre-roll of 0.02 s moves the legs" "$tmp/warned/report.md" ||
  fail "warned run's report.md has no such warning"
# The warnings give this command's flags, not simulate's option names.
grep -q "cloth on them may tear; --preroll 0.0[0-9] s or more keeps them under" "$tmp/warned.err" ||
  fail "the pre-roll warning does not name --preroll: $(cat "$tmp/warned.err")"
grep -q "option 'preroll'\|option 'stepRate'\|pinsYield" "$tmp/warned.err" "$tmp/warned/report.md" &&
  fail "a warning names simulate's options: $(grep "option 'preroll'\|option 'stepRate'\|pinsYield" "$tmp/warned.err")"

# 1c. A motion named with a space, "|", "]", "<!--" and "*": report.md
# escapes it in tables, headings and alt text (a "<!--" hid the rest of
# the report), and percent-encodes it in image links.
odd="walk 1|a]<!-- *x*"
cp "$resources/characters/walk_new.bvh" "$tmp/$odd.bvh" || fail "cannot copy the walk"
"$host" -q pipeline --levels 1 --instance-frames 2 --test-frames 1 --preroll 0.1 --size 64x64 \
  --test "$tmp/$odd.bvh" --out "$tmp/odd" > "$tmp/odd.out" 2> "$tmp/odd.err" ||
  { fail "odd-name run exit code $?"; cat "$tmp/odd.err"; }
[ -f "$tmp/odd/previews/sheet_$odd.png" ] || fail "no preview sheet named after the motion"
grep -qF '![walk 1\|a\]\<!-- \*x\*: every model at frame 0](previews/sheet_walk%201%7Ca%5D%3C!--%20*x*.png)' \
  "$tmp/odd/report.md" || fail "report.md: the sheet's image link is not escaped: $(grep -F 'sheet_' "$tmp/odd/report.md")"
grep -qxF '### walk 1\|a\]\<!-- \*x\*' "$tmp/odd/report.md" || fail "report.md: no escaped heading for the motion"
grep -qF '| multires_d5 |' "$tmp/odd/report.md" || fail "report.md: no table row for multires_d5"
grep -F 'walk 1|' "$tmp/odd/report.md" && fail "report.md: the motion's name unescaped"
grep -F ']<!--' "$tmp/odd/report.md" && fail "report.md: an HTML comment opened"

# 1d. A tall --size: four models' cells at half of it (64x4096) would make a
# contact sheet taller than preview.limits().sheetSide (16384): they shrink
# to fit, keeping their shape.
"$host" -q pipeline --levels 1 --instance-frames 2 --test-frames 1 --preroll 0.1 --size 64x8192 \
  --test "$resources/characters/walk_new.bvh" --out "$tmp/tall" > "$tmp/tall.out" 2> "$tmp/tall.err" ||
  { fail "tall run exit code $?"; cat "$tmp/tall.err"; }
# png_size <file>: "WIDTH HEIGHT" from the PNG's header.
png_size() { od -An -tu1 -j16 -N8 "$1" | awk '{ print $1 * 16777216 + $2 * 65536 + $3 * 256 + $4, $5 * 16777216 + $6 * 65536 + $7 * 256 + $8 }'; }
[ "$(png_size "$tmp/tall/previews/frames/coarse_walk_new_f0.png")" = "63 4053" ] ||
  fail "tall run's cell: $(png_size "$tmp/tall/previews/frames/coarse_walk_new_f0.png"), expected 63 4053"
[ "$(png_size "$tmp/tall/previews/sheet_walk_new.png" | cut -d' ' -f2)" -le 16384 ] ||
  fail "tall run's sheet: $(png_size "$tmp/tall/previews/sheet_walk_new.png")"

# 2. The script through the public API, same options (the default mode
# mapping spelled out) on two threads: same numbers.
"$host" -q -b "$resources/scripts/pipeline.js" -- $small --map-modes index --threads 2 --out "$tmp/script" > "$tmp/script.out" 2> "$tmp/script.err" ||
  { fail "pipeline.js exit code $?"; cat "$tmp/script.err"; }
"$host" -q -b "$scripts/pipeline_check.js" -- "$tmp/command" "$tmp/script" || fail "check command against script"

# 3. Resume: every stage skipped, the same numbers.
cp "$tmp/command/report.json" "$tmp/first_report.json"
"$host" pipeline $small --out "$tmp/command" --resume > "$tmp/resume.out" 2> "$tmp/resume.err" ||
  { fail "resume exit code $?"; cat "$tmp/resume.err"; }
grep -q "(0 stages run, 11 resumed)" "$tmp/resume.out" || fail "resume ran stages: $(cat "$tmp/resume.out")"
grep -q "complete from an earlier run, skipped" "$tmp/resume.err" || fail "no skip lines on stderr"
"$host" -q -b "$scripts/pipeline_check.js" -- "$tmp/command" "$tmp/script" || fail "check after resume"

# 4. Resume with other options is refused before any work.
"$host" -q pipeline $small --modes 3 --out "$tmp/command" --resume > /dev/null 2> "$tmp/other.err"
code=$?
[ "$code" -eq 1 ] || fail "resume with other options: exit code $code"
grep -q "holds a run with other options (--modes [0-9]* there, 3 now)" "$tmp/other.err" || fail "other options: $(cat "$tmp/other.err")"
# So is a run made before a change of solver defaults (its options.json
# names no revision): its results would mix with this build's.
cp "$tmp/command/stages/options.json" "$tmp/options.json.kept"
sed -i 's/"solverRevision":[0-9]*,//' "$tmp/command/stages/options.json"
grep -q solverRevision "$tmp/command/stages/options.json" && fail "the test could not remove the revision"
"$host" -q pipeline $small --out "$tmp/command" --resume > /dev/null 2> "$tmp/revision.err"
code=$?
[ "$code" -eq 1 ] || fail "resume of another solver revision: exit code $code"
grep -q "holds a run made with other solver defaults (revision 1; this build's [0-9]*)" "$tmp/revision.err" ||
  fail "other revision: $(cat "$tmp/revision.err")"
cp "$tmp/options.json.kept" "$tmp/command/stages/options.json"

# 4b. The solve, bend and motion smoothing options reach every run: the
# report says so, the runs' settings carry them, and the instance moves otherwise.
"$host" -q pipeline $small --newton-cg 1 --bend-model secondDifference --bend-stiffness 0.02 --motion-smoothing 0.01 \
  --out "$tmp/solve" \
  > "$tmp/solve.out" 2> "$tmp/solve.err" || { fail "solve options exit code $?"; cat "$tmp/solve.err"; }
grep -q "with bend stiffness 0.02 N/m (secondDifference bend springs); Newton steps of 1 CG" "$tmp/solve/report.md" ||
  fail "report.md does not name the solve: $(head -3 "$tmp/solve/report.md")"
grep -q "; clips smoothed in time by 0.01 s;" "$tmp/solve/report.md" ||
  fail "report.md does not name the smoothing: $(head -3 "$tmp/solve/report.md")"
for setting in '"newtonCg": 1' '"bendModel": "secondDifference"' '"bendStiffness": 0.02' '"motionSmoothing": 0.01'; do
  grep -q "$setting" "$tmp/solve/report.json" || fail "report.json lacks $setting"
done
cmp -s "$tmp/solve/caches/instance_high.pc2" "$tmp/command/caches/instance_high.pc2" &&
  fail "the solve options left the instance as it was"

# 5. Ctrl-C once the instance is recorded, during the test runs or previews
# (at 60 steps a second, which the finished report must say).
# (This shell starts a background job with SIGINT ignored, which the host
# keeps; a terminal's Ctrl-C finds it at its default, as env sets it here.)
env --default-signal=INT "$host" pipeline $small --test-frames 120 --step-rate 60 --out "$tmp/interrupted" > "$tmp/int.out" 2> "$tmp/int.err" &
pid=$!
tries=0
until [ -f "$tmp/interrupted/stages/modes.json" ]; do
  tries=$((tries + 1))
  if [ "$tries" -gt 600 ] || ! kill -0 "$pid" 2>/dev/null; then
    fail "the pipeline did not get to its modes"; cat "$tmp/int.err"; kill "$pid" 2>/dev/null; break
  fi
  sleep 0.1
done
sleep 1
kill -INT "$pid"
wait "$pid"
code=$?
[ "$code" -eq 130 ] || { fail "interrupted pipeline: exit code $code, expected 130"; tail -5 "$tmp/int.err"; }
tail -1 "$tmp/int.err" | grep -Eq "pipeline: stopped in \[[0-9]+/[0-9]+\] [a-z0-9_-]+ with [1-9][0-9]* stage\(s\) complete, which are kept; the same command with --resume continues from the stages complete" ||
  fail "the interrupted pipeline did not say how to go on: $(tail -2 "$tmp/int.err")"
leftovers=$(find "$tmp/interrupted" -name '.*tmp*')
[ -z "$leftovers" ] || fail "temporary files left behind: $leftovers"
[ -f "$tmp/interrupted/report.json" ] && fail "an interrupted run wrote a report"
# Every cache present is complete: the resumed run reads them all.
"$host" -q pipeline $small --test-frames 120 --step-rate 60 --out "$tmp/interrupted" --resume > "$tmp/int_resume.out" 2> "$tmp/int_resume.err" ||
  { fail "resume after Ctrl-C: exit code $?"; cat "$tmp/int_resume.err"; }
grep -q "resumed)" "$tmp/int_resume.out" && ! grep -q "(0 stages run" "$tmp/int_resume.out" ||
  fail "resume after Ctrl-C: $(cat "$tmp/int_resume.out")"
grep -Eq ", [1-9][0-9]* resumed\)" "$tmp/int_resume.out" || fail "nothing was resumed: $(cat "$tmp/int_resume.out")"
"$host" -q -b "$scripts/pipeline_check.js" -- "$tmp/interrupted" || fail "check the interrupted run at 60 steps a second"
grep -q "; 30 fps, 60 steps per second\." "$tmp/interrupted/report.md" || fail "report.md does not say 60 steps per second"

# 6. bench/distance_floor.js re-runs every model as the pipeline did: with
# no perturbation each distance comes out as the pipeline measured it.
"$host" -q -b "$resources/../bench/distance_floor.js" -- "$tmp/command" 0 > "$tmp/floor.out" 2> "$tmp/floor.err" ||
  { fail "distance_floor.js exit code $?"; cat "$tmp/floor.err"; }
grep -q "every re-run reproduces the pipeline's distances" "$tmp/floor.out" || fail "distance floor: $(cat "$tmp/floor.out")"
grep -Eq "^\| walk_new \| 0\.0 \| coarse " "$tmp/floor.out" || fail "distance floor table: $(cat "$tmp/floor.out")"

# 7. bench/still_drape.js runs every compared model on the test walk held
# at its first frame and measures each against the high-resolution mesh.
"$host" -q -b "$resources/../bench/still_drape.js" -- "$tmp/command" > "$tmp/still.out" 2> "$tmp/still.err" ||
  { fail "still_drape.js exit code $?"; cat "$tmp/still.err"; }
[ -s "$tmp/command/still/walk_new_still.bvh" ] || fail "still_drape.js wrote no held motion"
for model in coarse multires_d6 multires_d8; do
  grep -Eq "^\| $model \| [0-9]+ \| [0-9]+\.[0-9] \| [0-9]+\.[0-9] \| [0-9]+ % \| [0-9]+\.[0-9] \| [0-9]+\.[0-9] \|$" "$tmp/still.out" ||
    fail "still drape: no row for $model: $(cat "$tmp/still.out")"
done

# Options that are not a JSON object are refused by name, before any run.
if "$host" -q -b "$resources/../bench/still_drape.js" -- "$tmp/command" - - '[1]' > "$tmp/still_bad.out" 2> "$tmp/still_bad.err"; then
  fail "still_drape.js accepted options '[1]'"
fi
grep -q "options must be a JSON object of simulate options, got \[1\]" "$tmp/still_bad.err" ||
  fail "still_drape.js bad options: $(cat "$tmp/still_bad.err")"

[ "$failed" -eq 0 ] && echo "pipeline: ok"
exit "$failed"
