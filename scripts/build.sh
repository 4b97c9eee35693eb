#!/usr/bin/env bash
# Configures and builds mrcloth into ./build (Release). Extra arguments are
# passed to `cmake --build` (e.g. --target mrcloth).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="${MRCLOTH_BUILD_DIR:-$root/build}"
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j"$jobs" "$@"
