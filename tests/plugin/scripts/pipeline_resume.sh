#!/bin/sh
# --resume takes only what the same run made: not the stage records an
# earlier run with other options left in the folder, nor a folder whose
# record of its options is gone or broken, nor a run whose input files have
# changed since; a broken stage record is run again; --threads and --size may
# differ (the previews are rendered again), and other options are named as
# on the command line.
#
# pipeline_resume.sh <mrcloth> <resources> <tmp folder>
set -u
host=$1 resources=$2 tmp=$3
rm -rf "$tmp" && mkdir -p "$tmp" || exit 1
# Tiny: one test walk of one frame (11 stages), no pre-roll.
cheap="--levels 1 --instance-frames 2 --test-frames 1 --preroll 0 --size 64x64 --test $resources/characters/walk_new.bvh"
failed=0
fail() { echo "FAILED: $*"; failed=1; }
# ran <name> <pipeline arguments...>: a run that must succeed; its stdout in $tmp/<name>.out, stderr in .err.
ran() {
  name=$1
  shift
  "$host" pipeline "$@" > "$tmp/$name.out" 2> "$tmp/$name.err" || { fail "$name: exit code $?"; cat "$tmp/$name.err"; }
}
# refused <name> <stderr regex> <pipeline arguments...>: exit 1, the message, no script stack.
refused() {
  name=$1 pattern=$2
  shift 2
  "$host" pipeline "$@" > "$tmp/$name.out" 2> "$tmp/$name.err"
  code=$?
  [ "$code" -eq 1 ] || fail "$name: exit code $code, expected 1"
  grep -Eq -e "$pattern" "$tmp/$name.err" || fail "$name: stderr does not match '$pattern': $(cat "$tmp/$name.err")"
  grep -q '^    at ' "$tmp/$name.err" && fail "$name: a script stack on stderr: $(cat "$tmp/$name.err")"
}

# 1. A run with other options (3 instance frames) left its stage records in
# the folder a new run (2 frames) then stopped in: resumed, the new run
# takes none of them.
ran first -q $cheap --instance-frames 3 --out "$tmp/first"
ran second -q $cheap --out "$tmp/run"
for record in "$tmp"/first/stages/*.json; do
  [ "$(basename "$record")" = options.json ] || cp "$record" "$tmp/run/stages/"
done
ran stale -q $cheap --out "$tmp/run" --resume
grep -q "(11 stages run, 0 resumed)" "$tmp/stale.out" || fail "stale records were resumed: $(cat "$tmp/stale.out")"
grep -A3 '"table1Instance"' "$tmp/run/report.json" | grep -q '"frames": 2,' ||
  fail "the report's instance is not the run's 2 frames: $(grep -A3 '"table1Instance"' "$tmp/run/report.json")"

# 2. A folder without its record of the run's options is not resumed.
cp "$tmp/run/stages/options.json" "$tmp/options.json.kept"
rm "$tmp/run/stages/options.json"
refused no_options "--resume: .*/run holds no stages/options.json.*; run without --resume" $cheap --out "$tmp/run" --resume
head -c 60 "$tmp/options.json.kept" > "$tmp/run/stages/options.json"
refused broken_options "--resume: .*/run/stages/options.json is unreadable .*; run without --resume" \
  $cheap --out "$tmp/run" --resume
cp "$tmp/options.json.kept" "$tmp/run/stages/options.json"

# 3. Other options are named as given on the command line; --threads and
# --size are not results: the run resumes, rendering its previews again.
refused other_options "holds a run with other options \(--modes 3 there, 2 now; --instance-frames [0-9]+ there, 3 now\)" \
  $cheap --instance-frames 3 --modes 2 --out "$tmp/run" --resume
refused other_smoothing "holds a run with other options \(--motion-smoothing not given there, 0.01 now\)" \
  $cheap --motion-smoothing 0.01 --out "$tmp/run" --resume
ran threads_size $cheap --threads 2 --size 80x80 --out "$tmp/run" --resume
grep -q "(1 stages run, 10 resumed)" "$tmp/threads_size.out" || fail "--threads/--size resume: $(cat "$tmp/threads_size.out")"
# Defaults given by name are the defaults (they were taken for other options).
ran named_defaults $cheap --step-rate 120 --limiter-acceleration auto --size 80x80 --out "$tmp/run" --resume
grep -q "(0 stages run, 11 resumed)" "$tmp/named_defaults.out" || fail "named defaults: $(cat "$tmp/named_defaults.out")"
grep -q "previews \.\.\.$" "$tmp/threads_size.err" || fail "the previews were not rendered again: $(cat "$tmp/threads_size.err")"

# 4. A broken stage record (cut short, or no record at all) is run again, with a warning naming it.
head -c 100 "$tmp/run/stages/modes.json" > "$tmp/modes.json" && mv "$tmp/modes.json" "$tmp/run/stages/modes.json"
echo '{}' > "$tmp/run/stages/compare-walk_new.json"
ran broken_record $cheap --size 80x80 --out "$tmp/run" --resume
grep -q "(2 stages run, 9 resumed)" "$tmp/broken_record.out" || fail "broken records: $(cat "$tmp/broken_record.out")"
grep -q "\[warn\] pipeline: .*/run/stages/modes.json is unreadable .*; running modes again" "$tmp/broken_record.err" ||
  fail "no warning naming modes.json: $(cat "$tmp/broken_record.err")"
grep -q "\[warn\] pipeline: .*/run/stages/compare-walk_new.json is not a stage record" "$tmp/broken_record.err" ||
  fail "no warning naming compare-walk_new.json: $(cat "$tmp/broken_record.err")"

# 5. A stage's output cut short, or edited at the same size, since its stage
# wrote it: named, and that stage alone is run again.
size=$(wc -c < "$tmp/run/caches/instance_high.pc2")
head -c $((size / 2)) "$tmp/run/caches/instance_high.pc2" > "$tmp/cut.pc2" && mv "$tmp/cut.pc2" "$tmp/run/caches/instance_high.pc2"
ran cut_output $cheap --size 80x80 --out "$tmp/run" --resume
grep -q "(1 stages run, 10 resumed)" "$tmp/cut_output.out" || fail "a cut cache: $(cat "$tmp/cut_output.out")"
grep -q "\[warn\] pipeline: .*/run/caches/instance_high.pc2 is not the file instance wrote (now $((size / 2)) bytes, then $size); running instance again" \
  "$tmp/cut_output.err" || fail "no warning naming the cut cache: $(cat "$tmp/cut_output.err")"
[ "$(wc -c < "$tmp/run/caches/instance_high.pc2")" -eq "$size" ] || fail "the cache was not written again whole"
ply="$tmp/run/meshes/high_by_level.ply"
sed '1s/ply/PLY/' "$ply" > "$tmp/edited.ply" && mv "$tmp/edited.ply" "$ply"
ran edited_output $cheap --size 80x80 --out "$tmp/run" --resume
grep -q "(1 stages run, 10 resumed)" "$tmp/edited_output.out" || fail "an edited mesh: $(cat "$tmp/edited_output.out")"
grep -q "\[warn\] pipeline: .*/run/meshes/high_by_level.ply is not the file refine-uniform wrote (the same size, other contents); running refine-uniform again" \
  "$tmp/edited_output.err" || fail "no warning naming the edited mesh: $(cat "$tmp/edited_output.err")"
head -1 "$ply" | grep -qx "ply" || fail "the edited mesh was not written again"
# An output deleted, and a record whose fingerprints are damaged: named, run again.
rm "$tmp/run/meshes/uniform_equal.om"
sed 's/"files": \[/"files": [null,/' "$tmp/run/stages/modes.json" > "$tmp/modes_damaged.json" &&
  mv "$tmp/modes_damaged.json" "$tmp/run/stages/modes.json"
ran gone_output $cheap --size 80x80 --out "$tmp/run" --resume
grep -q "(2 stages run, 9 resumed)" "$tmp/gone_output.out" || fail "a deleted output, a damaged record: $(cat "$tmp/gone_output.out")"
grep -q "\[warn\] pipeline: .*/run/meshes/uniform_equal.om, which refine-equal wrote, is gone; running refine-equal again" \
  "$tmp/gone_output.err" || fail "no warning naming the deleted output: $(cat "$tmp/gone_output.err")"
grep -q "\[warn\] pipeline: .*/run/stages/modes.json does not hold a size and SHA-256 for each of its files; running modes again" \
  "$tmp/gone_output.err" || fail "no warning naming the damaged record: $(cat "$tmp/gone_output.err")"

# 5b. The files a stage names only once it ran (--obj-sequence's frames,
# --sequence's images and animation, the contact sheets' cells) are checked
# as its others: one deleted or cut short runs its stage again.
extras="$cheap --obj-sequence --sequence --out $tmp/extras"
ran extras_first -q $extras
obj="$tmp/extras/caches/coarse_walk_new_0000.obj"
cell="$tmp/extras/previews/frames/coarse_walk_new_f0.png"
[ -f "$obj" ] && [ -f "$cell" ] || fail "no $obj or $cell to damage: $(ls "$tmp/extras/caches" "$tmp/extras/previews/frames")"
grep -q '"caches/coarse_walk_new_0000.obj"' "$tmp/extras/stages/simulate-coarse-walk_new.json" ||
  fail "the coarse run's record lists no OBJ frame"
size=$(wc -c < "$obj")
head -c $((size - 1)) "$obj" > "$tmp/cut.obj" && mv "$tmp/cut.obj" "$obj"
rm "$cell"
ran extras_damaged $extras --resume
grep -q "(2 stages run, 9 resumed)" "$tmp/extras_damaged.out" || fail "damaged extra files: $(cat "$tmp/extras_damaged.out")"
grep -q "\[warn\] pipeline: .*/extras/caches/coarse_walk_new_0000.obj is not the file simulate-coarse-walk_new wrote (now $((size - 1)) bytes, then $size)" \
  "$tmp/extras_damaged.err" || fail "no warning naming the cut OBJ frame: $(cat "$tmp/extras_damaged.err")"
grep -q "\[warn\] pipeline: .*/extras/previews/frames/coarse_walk_new_f0.png, which previews wrote, is gone; running previews again" \
  "$tmp/extras_damaged.err" || fail "no warning naming the deleted cell: $(cat "$tmp/extras_damaged.err")"
[ "$(wc -c < "$obj")" -eq "$size" ] && [ -f "$cell" ] || fail "the damaged extra files were not written again"
ran extras_whole -q $extras --resume
grep -q "(0 stages run, 11 resumed)" "$tmp/extras_whole.out" || fail "a whole run with extras: $(cat "$tmp/extras_whole.out")"

# 6. One run at a time per folder. A fresh run removes the report an earlier
# run left before any stage (it would stand beside this run's outputs); a
# second run on the folder is refused naming the first; killed (SIGKILL),
# the first leaves its lock and a temporary file, which a resume takes over
# and removes.
long="--levels 1 --instance-frames 20 --test-frames 300 --preroll 0 --size 64x64 --test $resources/characters/walk_new.bvh"
ran earlier -q $cheap --out "$tmp/locked"
[ -f "$tmp/locked/report.md" ] || fail "the earlier run wrote no report"
"$host" -q pipeline $long --out "$tmp/locked" > "$tmp/first_run.out" 2> "$tmp/first_run.err" &
first=$!
tries=0
until [ -f "$tmp/locked/stages/.lock" ] && [ ! -f "$tmp/locked/report.md" ] && [ -f "$tmp/locked/stages/instance.json" ]; do
  tries=$((tries + 1))
  if [ "$tries" -gt 600 ] || ! kill -0 "$first" 2>/dev/null; then
    fail "the first run did not get to its instance holding the lock"; cat "$tmp/first_run.err"; break
  fi
  sleep 0.1
done
refused second "option --out: .*/locked is in use by another pipeline run \(mrcloth process $first( on [^)]*)?\); wait for it to end, or use another --out" \
  $cheap --out "$tmp/locked"
echo x > "$tmp/locked/caches/.walk_new.pc2.tmp-1a2b-0.pc2"
kill -KILL "$first"
wait "$first" 2>/dev/null
[ -f "$tmp/locked/stages/.lock" ] || fail "the killed run left no lock (the test would not test taking one over)"
[ -f "$tmp/locked/report.md" ] && fail "the killed run left the earlier run's report"
ran taken_over $long --out "$tmp/locked" --resume
grep -Eq ", [1-9][0-9]* resumed\)" "$tmp/taken_over.out" || fail "nothing resumed after the kill: $(cat "$tmp/taken_over.out")"
# (The killed run may have left one of its own too.)
grep -Eq "pipeline: removed [1-9][0-9]* temporary files? an interrupted writer left \(.*/locked/" \
  "$tmp/taken_over.err" || fail "no temporary was said removed: $(cat "$tmp/taken_over.err")"
leftovers=$(find "$tmp/locked" -name '.*tmp*')
[ -z "$leftovers" ] || fail "temporary files left behind: $leftovers"
[ -f "$tmp/locked/stages/.lock" ] && fail "the run left its lock behind"
# A lock naming no process (killed while creating it) is taken over once
# older than a few seconds; a folder inside --out that is not the run's own
# (another run's --out) keeps its temporaries.
: > "$tmp/locked/stages/.lock" && touch -d '1 minute ago' "$tmp/locked/stages/.lock"
mkdir -p "$tmp/locked/other_run" && echo x > "$tmp/locked/other_run/.cache.pc2.tmp-1a2b-0.pc2"
ran ownerless -q $long --out "$tmp/locked" --resume
[ -f "$tmp/locked/other_run/.cache.pc2.tmp-1a2b-0.pc2" ] || fail "a temporary outside the run's folders was removed"

# 7. An input file changed in place (two vertices swapped: the same size) is
# named; so is one whose size changed. Nothing is written.
cp "$resources/garments/default_skirt.obj" "$tmp/skirt.obj"
ran garment -q $cheap --garment "$tmp/skirt.obj" --out "$tmp/garment"
cp "$tmp/garment/report.json" "$tmp/garment_report.json"
awk '/^v / && n < 2 { n++; if (n == 1) { first = $0; next } print; print first; next } { print }' \
  "$resources/garments/default_skirt.obj" > "$tmp/skirt.obj"
cmp -s "$tmp/skirt.obj" "$resources/garments/default_skirt.obj" && fail "the test could not change the garment"
refused changed "--resume: .*skirt.obj \(--garment\) has changed since the run in .*/garment began \(the same size, other contents\)" \
  $cheap --garment "$tmp/skirt.obj" --out "$tmp/garment" --resume
echo "# one more line" >> "$tmp/skirt.obj"
refused grown "--resume: .*skirt.obj \(--garment\) has changed since the run .* \(now [0-9]+ bytes, then [0-9]+\)" \
  $cheap --garment "$tmp/skirt.obj" --out "$tmp/garment" --resume
cmp -s "$tmp/garment/report.json" "$tmp/garment_report.json" || fail "a refused resume rewrote the report"

[ "$failed" -eq 0 ] && echo "pipeline resume: ok"
exit "$failed"
