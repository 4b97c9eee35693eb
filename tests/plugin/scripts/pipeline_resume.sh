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
refused other_options "holds a run with other options \(--modes, --instance-frames\)" \
  $cheap --instance-frames 3 --modes 2 --out "$tmp/run" --resume
ran threads_size $cheap --threads 2 --size 80x80 --out "$tmp/run" --resume
grep -q "(1 stages run, 10 resumed)" "$tmp/threads_size.out" || fail "--threads/--size resume: $(cat "$tmp/threads_size.out")"
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

# 5. An input file changed in place (two vertices swapped: the same size) is
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
