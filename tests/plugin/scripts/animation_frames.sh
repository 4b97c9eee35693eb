#!/bin/sh
# renderSequence's animations take the frames drawn, in the order asked:
# stand-in encoders (ImageMagick's convert and ffmpeg, first on PATH) write
# down the images they were given, resolved, and make the output file. The
# MP4 took the images' numbered pattern instead: with frames [5, 2, 4] it
# read whatever its prefix's folder held from frame 2 on, an earlier run's
# frames too.
#
# animation_frames.sh <mrcloth> <tests/data> <tmp folder>
set -u
host=$1 data=$2 tmp=$3
rm -rf "$tmp" && mkdir -p "$tmp/bin" "$tmp/frames" || exit 1
# The stand-ins: every argument that names an image (ffmpeg's pattern
# expanded in order), resolved through links, one per line in <tool>.list.
cat > "$tmp/bin/convert" <<SH
#!/bin/sh
for a in "\$@"; do case "\$a" in *.png) readlink -f "\$a" ;; esac; done > "$tmp/convert.list"
for a in "\$@"; do last=\$a; done; : > "\$last"
SH
cat > "$tmp/bin/ffmpeg" <<SH
#!/bin/sh
previous=""
for a in "\$@"; do
  if [ "\$previous" = "-i" ]; then
    folder=\$(dirname "\$a"); ls "\$folder" | sort | while read -r f; do readlink -f "\$folder/\$f"; done
  fi
  previous=\$a
done > "$tmp/ffmpeg.list"
for a in "\$@"; do last=\$a; done; : > "\$last"
SH
chmod +x "$tmp/bin/convert" "$tmp/bin/ffmpeg"
cat > "$tmp/animate.js" <<'JS'
"use strict";
const [dataDir, tmpDir] = core.scriptArguments();
const grid = core.loadObject(dataDir + "/grid3x3.obj");
multirescloth.simulate(grid, {frames: 8, pins: [0, 1, 2, 3], output: tmpDir + "/sheet.pc2"});
const small = {cache: tmpDir + "/sheet.pc2", width: 32, height: 32, supersample: 1};
// An earlier run's frames under the same prefix, which the MP4 must not take.
preview.renderSequence(grid, tmpDir + "/frames/f", small);
for (const format of ["gif", "mp4"])
  preview.renderSequence(grid, tmpDir + "/frames/f", Object.assign({frames: [5, 2, 4], animation: tmpDir + "/a." + format}, small));
print("animations asked");
JS
PATH="$tmp/bin:$PATH" "$host" -q -b "$tmp/animate.js" -- "$data" "$tmp" > "$tmp/stdout" 2> "$tmp/stderr"
code=$?
failed=0
[ "$code" -eq 0 ] || { echo "exit code $code"; cat "$tmp/stderr"; failed=1; }
frames=$(cd "$tmp/frames" && pwd -P)
printf '%s\n' "$frames/f_0005.png" "$frames/f_0002.png" "$frames/f_0004.png" > "$tmp/expected.list"
for tool in convert ffmpeg; do
  cmp -s "$tmp/$tool.list" "$tmp/expected.list" ||
    { echo "$tool was given:"; cat "$tmp/$tool.list"; echo "expected:"; cat "$tmp/expected.list"; failed=1; }
done
[ -e "$tmp/a.gif" ] && [ -e "$tmp/a.mp4" ] || { echo "no animation made: $(ls "$tmp")"; failed=1; }
[ "$failed" -eq 0 ] && echo "animation frames: ok"
exit "$failed"
