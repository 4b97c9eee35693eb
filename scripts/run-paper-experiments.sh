#!/usr/bin/env bash
# The paper's experiments on the shared real data (issue 7): the MakeHuman
# skirt and trousers on the skinned MakeHuman body, instance CMU 07_06 (200
# frames after the pre-roll), test walks 07_03, 08_03, 02_01 and the squat,
# each through `mrcloth pipeline`, with --resume where the output folder
# holds a run already, so an interrupted run continues where it stopped.
# Long: the skinned-mesh collisions of the high-resolution garments
# dominate (see README, Known limits).
#
# Usage: scripts/run-paper-experiments.sh [shared data folder] [output folder] [pipeline options...]
#   defaults: ../shared/data beside the checkout, ./paper_out
#   pipeline options are appended (e.g. --instance-frames 20 for a quick look).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
data="${1:-$root/../shared/data}"
out="${2:-paper_out}"
shift $(( $# < 2 ? $# : 2 ))
build="${MRCLOTH_BUILD_DIR:-$root/build}"
motions="$data/motions/cmu_mb"
makehuman="$data/bodies/makehuman"
for file in "$makehuman/base.obj" "$motions/07_06.bvh" "$motions/07_03.bvh" "$motions/08_03.bvh" \
            "$motions/02_01.bvh" "$motions/13_29_squats_f3760-4580.bvh" \
            "$data/garments/makehuman/skirthelper.obj" "$data/garments/makehuman/male_casualsuit04_pants_on_base.obj"; do
  if [ ! -f "$file" ]; then
    echo "run-paper-experiments: $file is missing: the shared data must sit beside the checkout (or pass its folder)" >&2
    exit 2
  fi
done
[ -x "$build/bin/mrcloth" ] || bash "$root/scripts/build.sh" --target mrcloth
for garment in skirthelper male_casualsuit04_pants_on_base; do
  # --resume continues a run the folder holds; a new folder starts one.
  resume=()
  [ -f "$out/$garment/stages/options.json" ] && resume=(--resume)
  "$build/bin/mrcloth" pipeline "${resume[@]}" \
    --garment "$data/garments/makehuman/$garment.obj" --makehuman "$makehuman" --body mesh --motion-units cmu \
    --instance "$motions/07_06.bvh" \
    --test "$motions/07_03.bvh,$motions/08_03.bvh,$motions/02_01.bvh,$motions/13_29_squats_f3760-4580.bvh" \
    --out "$out/$garment" "$@"
  echo "run-paper-experiments: $garment -> $out/$garment/report.md"
done
