#!/bin/sh
# scripts/run-paper-experiments.sh, issue 7's command, on the shared data at
# a tiny size: from a new output folder it runs (it once passed --resume
# there, which refuses a folder without a run), and run again it resumes
# every stage. Skipped (exit 77) without the shared data.
#
# paper_experiments_test.sh <source folder> <build folder> <shared data> <tmp folder>
set -u
source_dir=$1 build=$2 data=$3 tmp=$4
if [ ! -f "$data/bodies/makehuman/base.obj" ]; then
  echo "SKIP: $data holds no MakeHuman body (the shared data folder is not beside the checkout)"
  exit 77
fi
rm -rf "$tmp" && mkdir -p "$tmp" || exit 1
tiny="--levels 1 --modes 2 --delta 6 --instance-frames 2 --test-frames 1 --preroll 0.1 --size 64x64"
failed=0
fail() { echo "FAILED: $*"; failed=1; }
MRCLOTH_BUILD_DIR=$build bash "$source_dir/scripts/run-paper-experiments.sh" "$data" "$tmp/out" $tiny \
  > "$tmp/first.out" 2> "$tmp/first.err" || { fail "first run: exit code $?"; tail -5 "$tmp/first.err"; }
for garment in skirthelper male_casualsuit04_pants_on_base; do
  [ -f "$tmp/out/$garment/report.md" ] || fail "no report for $garment"
done
[ "$(grep -c "([1-9][0-9]* stages run, 0 resumed)" "$tmp/first.out")" -eq 2 ] ||
  fail "the first run did not run both garments afresh: $(cat "$tmp/first.out")"
MRCLOTH_BUILD_DIR=$build bash "$source_dir/scripts/run-paper-experiments.sh" "$data" "$tmp/out" $tiny \
  > "$tmp/again.out" 2> "$tmp/again.err" || { fail "second run: exit code $?"; tail -5 "$tmp/again.err"; }
[ "$(grep -c "(0 stages run, [0-9]* resumed)" "$tmp/again.out")" -eq 2 ] ||
  fail "run again, a garment ran stages: $(cat "$tmp/again.out")"
[ "$failed" -eq 0 ] && echo "paper experiments: ok"
exit "$failed"
