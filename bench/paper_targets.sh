#!/usr/bin/env bash
# Issue 7's targets table (bench/paper_targets.js) for pipeline runs.
#
# Usage: bench/paper_targets.sh                 run the pipeline on the embedded default
#                                               into bench_out/pipeline (--resume), then judge it
#        bench/paper_targets.sh OUT_DIR ...     judge finished runs, e.g. the folders
#                                               scripts/run-paper-experiments.sh writes
# Times are one core's (the pipeline's default --threads 1; paper_targets.js refuses
# reports run on more); quote ratios from one run.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="${MRCLOTH_BUILD_DIR:-$root/build}"
[ -x "$build/bin/mrcloth" ] || bash "$root/scripts/build.sh" --target mrcloth
if [ $# -eq 0 ]; then
  # --resume only where a run began (it refuses a folder without one).
  resume=()
  [ -f bench_out/pipeline/stages/options.json ] && resume=(--resume)
  "$build/bin/mrcloth" pipeline "${resume[@]}" --out bench_out/pipeline
  set -- bench_out/pipeline
fi
exec "$build/bin/mrcloth" -q -b "$root/bench/paper_targets.js" -- "$@"
