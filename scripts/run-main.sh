#!/usr/bin/env bash
# The main job on the embedded default: installs dependencies (Debian 12),
# builds, and runs `mrcloth pipeline` (resources/scripts/pipeline.js) through
# the headless host: refinement, the instance, modes, multi-resolution
# meshes, every model on the test motions, previews and report.md.
# Usage: scripts/run-main.sh [output-folder [pipeline options...]]   (default: ./out)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/scripts/install-deps.sh"
bash "$root/scripts/build.sh" --target mrcloth
build="${MRCLOTH_BUILD_DIR:-$root/build}"
out="${1:-out}"
shift || true
exec "$build/bin/mrcloth" pipeline --out "$out" "$@"
