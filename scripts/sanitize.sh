#!/usr/bin/env bash
# Builds every target under AddressSanitizer and UndefinedBehaviorSanitizer
# into ./build-sanitize (RelWithDebInfo, no benchmarks) and runs the test
# suite there. A developer run, not part of CI: building takes about 25
# minutes on 2 cores, the suite about four times its usual time. Extra
# arguments go to ctest (e.g. -R GarmentMutations).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="${MRCLOTH_SANITIZE_DIR:-$root/build-sanitize}"
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMRCLOTH_SANITIZE=address,undefined \
  -DMRCLOTH_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" -j"$jobs"
# asan.supp: reports from inside Qt's script engine, not ours. A huge
# allocation throws std::bad_alloc, as it does without the checker (the
# loaders turn it into an InputError), instead of stopping the process.
# intercept_tls_get_addr=0: GCC 12's runtime takes a dynamic TLS block that
# merely sits at a glibc-2.19 header's offset for one, and LeakSanitizer's
# tracer then crashed at exit scanning a bogus range (once enough Qt plugins
# are loaded; google/sanitizers#1322): leaks are still checked.
export ASAN_OPTIONS="suppressions=$root/cmake/asan.supp:allocator_may_return_null=1:detect_leaks=1:intercept_tls_get_addr=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
ctest --test-dir "$build" -j"$jobs" --output-on-failure "$@"
