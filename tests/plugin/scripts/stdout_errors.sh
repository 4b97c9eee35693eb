#!/bin/sh
# Output lost to a failed write on stdout (a full disk; here /dev/full) must
# not pass for success: the host says so on stderr and exits 1, for a
# script's output as for --version and --api.
#
# stdout_errors.sh <mrcloth> <tmp folder>
set -u
host=$1 tmp=$2
[ -w /dev/full ] || { echo "SKIP: no /dev/full"; exit 77; }
rm -rf "$tmp" && mkdir -p "$tmp" || exit 1
printf '%s\n' 'print(JSON.stringify({a: 1}));' > "$tmp/print.js"
failed=0
check() {  # check <name> <args...>: stdout to /dev/full must fail with the reason
  name=$1; shift
  "$host" "$@" > /dev/full 2> "$tmp/$name.err"
  code=$?
  [ "$code" -eq 1 ] || { echo "$name: exit code $code, expected 1"; failed=1; }
  grep -q '^\[error\] cannot write to stdout: No space left on device$' "$tmp/$name.err" ||
    { echo "$name: no error naming the reason:"; cat "$tmp/$name.err"; failed=1; }
}
check script -q -b "$tmp/print.js"
check version --version
check api --api
check help --help
# The same commands with a working stdout still succeed.
"$host" -q -b "$tmp/print.js" > "$tmp/print.out" 2>&1 || { echo "script fails with a working stdout"; failed=1; }
grep -q '^{"a":1}$' "$tmp/print.out" || { echo "script output lost with a working stdout"; failed=1; }
[ "$failed" -eq 0 ] && echo "stdout errors: ok"
exit "$failed"
