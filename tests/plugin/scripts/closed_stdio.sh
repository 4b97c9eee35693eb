#!/bin/sh
# Started with stdin, stdout and stderr closed (a daemon, some schedulers),
# the host once wrote its progress lines into the PC2 cache it had open,
# which took descriptor 2. The same script run with and without them must
# write the same bytes (the simulation is deterministic).
#
# closed_stdio.sh <mrcloth> <tests/data> <tmp folder>
set -u
host=$1 data=$2 tmp=$3
rm -rf "$tmp" && mkdir -p "$tmp/open" "$tmp/closed" || exit 1
script="$tmp/write_cache.js"
cat > "$script" <<'JS'
"use strict";
const [dataDir, outDir] = core.scriptArguments();
const grid = multirescloth.refineUniform(core.loadObject(dataDir + "/grid3x3.obj"), 1);
multirescloth.simulate(grid, {frames: 30, pins: "top", output: outDir + "/sheet.pc2"});
core.log("a log line after the cache");
core.writeTextFile(outDir + "/text.txt", "text\n");
print("printed");
JS
# Progress on every frame: many lines while the cache is open.
export MRCLOTH_PROGRESS_INTERVAL=0.000001 MRCLOTH_PROGRESS=lines
"$host" -b "$script" -- "$data" "$tmp/open" > "$tmp/stdout" 2> "$tmp/stderr"
code_open=$?
"$host" -b "$script" -- "$data" "$tmp/closed" <&- >&- 2>&-
code_closed=$?
failed=0
[ "$code_open" -eq 0 ] || { echo "exit code $code_open with stdio open"; cat "$tmp/stderr"; failed=1; }
[ "$code_closed" -eq 0 ] || { echo "exit code $code_closed with stdio closed"; failed=1; }
grep -q '^\[job\] simulate: 2/30' "$tmp/stderr" || { echo "no progress lines: the test checks nothing"; failed=1; }
for file in sheet.pc2 sheet.obj text.txt; do
  cmp "$tmp/open/$file" "$tmp/closed/$file" || { echo "$file differs with stdio closed"; failed=1; }
done
[ "$failed" -eq 0 ] && echo "closed stdio: ok"
exit "$failed"
