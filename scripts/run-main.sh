#!/usr/bin/env bash
# The main job on the embedded default: installs dependencies (Debian 12),
# builds, and runs resources/scripts/main_job.js through the headless host.
# Usage: scripts/run-main.sh [output-folder]   (default: ./out)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/scripts/install-deps.sh"
bash "$root/scripts/build.sh" --target mrcloth mrcloth_multirescloth
build="${MRCLOTH_BUILD_DIR:-$root/build}"
exec "$build/bin/mrcloth" -b "$root/resources/scripts/main_job.js" -- "${1:-out}"
