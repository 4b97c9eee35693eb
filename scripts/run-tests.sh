#!/usr/bin/env bash
# Every test: installs dependencies (Debian 12), builds everything, runs ctest
# in parallel. Tests that need ../shared/data skip with a message without it.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/scripts/install-deps.sh"
bash "$root/scripts/build.sh"
build="${MRCLOTH_BUILD_DIR:-$root/build}"
jobs=$(nproc 2>/dev/null || echo 2)
ctest --test-dir "$build" -j"$jobs" --output-on-failure --timeout 600
