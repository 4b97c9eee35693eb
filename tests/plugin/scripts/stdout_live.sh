#!/bin/sh
# What a script prints reaches a file or pipe as it is printed, --quiet too:
# a line printed before a long call is in the file while the call runs, and
# survives SIGKILL (stdout was block buffered: the file stayed empty until
# the host exited, and a kill lost it).
#
# stdout_live.sh <mrcloth> <tmp folder>
set -u
. "$(dirname "$0")/wait_helpers.sh"
host=$1 tmp=$2
rm -rf "$tmp" && mkdir -p "$tmp" || exit 1
cat > "$tmp/long.js" <<'JS'
"use strict";
print("before the long call");
const end = Date.now() + 300000;
while (Date.now() < end) {}  // five minutes of work, which the test does not wait for
print("not reached");
JS
"$host" -q -b "$tmp/long.js" > "$tmp/stdout" 2> "$tmp/stderr" &
pid=$!
# wait_for_line fails the test (and kills the host) after 60 s without the line.
wait_for_line "$tmp/stdout" '^before the long call$' "$pid" "the printed line"
kill -KILL "$pid"
wait "$pid" 2>/dev/null
failed=0
grep -qx 'before the long call' "$tmp/stdout" || { echo "the line was lost on SIGKILL"; failed=1; }
grep -q 'not reached' "$tmp/stdout" && { echo "the long call finished: the test proved nothing"; failed=1; }
[ "$failed" -eq 0 ] && echo "stdout live: ok"
exit "$failed"
