#!/bin/sh
# Bad pipeline inputs stop before any work: exit code 1, a message naming
# the option or file (and no script stack), and no output folder created.
#
# pipeline_errors.sh <mrcloth> <resources> <tmp folder>
set -u
host=$1 resources=$2 tmp=$3
rm -rf "$tmp" && mkdir -p "$tmp" || exit 1
failed=0
n=0
# refused <stderr regex> <pipeline arguments...>
refused() {
  pattern=$1
  shift
  n=$((n + 1))
  out="$tmp/out$n"
  "$host" pipeline --out "$out" "$@" > "$tmp/stdout$n" 2> "$tmp/stderr$n"
  code=$?
  if [ "$code" -ne 1 ]; then echo "FAILED ($*): exit code $code, expected 1"; failed=1; fi
  if ! grep -Eq "$pattern" "$tmp/stderr$n"; then
    echo "FAILED ($*): stderr does not match '$pattern':"; cat "$tmp/stderr$n"; failed=1
  fi
  if [ -e "$out" ]; then echo "FAILED ($*): $out was created"; failed=1; fi
  # A command's user gets the message, not the pipeline script's stack.
  if grep -q '^    at ' "$tmp/stderr$n"; then echo "FAILED ($*): a script stack on stderr:"; cat "$tmp/stderr$n"; failed=1; fi
}
refused "unknown option \"--frobnicate\"" --frobnicate
refused "unexpected argument \"stray\"" stray
refused "option --levels: expected an integer >= 1, got \"two\"" --levels two
refused "option --levels: expected an integer >= 1, got \"0\"" --levels 0
refused "option --delta: expected a number > 0, got \"-3\"" --delta 8,-3
refused "option --fps: expected a number >= 1 and <= 100000, got \"fast\"" --fps fast
refused "option --threads: expected an integer >= 0 and <= 1024, got \"-2\"" --threads -2
refused "option --step-rate: expected a number > 0, got \"0\"" --step-rate 0
refused "option --step-rate: expected at least --fps \(30 frames per second\), got 20" --step-rate 20
refused "option --limiter-acceleration: expected auto or a number >= 0 and < 1, got \"fast\"" --limiter-acceleration fast
refused "option --limiter-acceleration: expected auto or a number >= 0 and < 1, got \"1\"" --limiter-acceleration 1
refused "option --newton-cg: expected an integer >= 0 and <= 1000, got \"-1\"" --newton-cg -1
refused "option --bend-model: expected one of distance, secondDifference, got \"hinge\"" --bend-model hinge
refused "option --bend-stiffness: expected a number >= 0, got \"-0.1\"" --bend-stiffness -0.1
refused "option --waist-smoothing: expected a number >= 0 and <= 1, got \"-0.01\"" --waist-smoothing -0.01
refused "option --waist-smoothing needs --makehuman DIR" --waist-smoothing 0.03
refused "option --motion-smoothing: expected a number >= 0 and <= 1, got \"1.5\"" --motion-smoothing 1.5
refused "option --motion-smoothing: expected a number >= 0 and <= 1, got \"x\"" --motion-smoothing x
refused "option --makehuman-units needs --makehuman DIR" --makehuman-units cm
refused "option --makehuman-units: expected one of" --makehuman-units cmu --makehuman "$tmp"
refused "option --body: expected one of capsules, mesh, got \"robot\"" --body robot
refused "option --map-modes: expected one of index, highest, frequent, got \"nearest\"" --map-modes nearest
refused "option --units: expected one of m, dm, cm, mm, inch, got \"feet\"" --units feet
refused "option --size: expected WIDTHxHEIGHT" --size 800
refused "option --size: 8000x8000 is 64000000 pixels; expected at most 33554432" --size 8000x8000
refused "option --modes needs a value" --modes
refused "option --garment: no such file: .*missing.obj" --garment "$tmp/missing.obj"
refused "option --test: no such file: .*nowhere.bvh" --test "$resources/characters/walk_new.bvh,$tmp/nowhere.bvh"
refused "option --instance: no such file" --instance "$tmp/no.bvh"
mkdir -p "$tmp/other" && cp "$resources/characters/walk_new.bvh" "$tmp/other/walk_new.bvh"
refused "option --test: .*walk_new.bvh and .*other/walk_new.bvh share the name \"walk_new\"" \
  --test "$resources/characters/walk_new.bvh" --test "$tmp/other/walk_new.bvh"
refused "option --body mesh needs --makehuman DIR" --body mesh
refused "option --makehuman: no such file: .*base.obj" --makehuman "$tmp" --units m
refused "option --makehuman needs --garment FILE, a garment modelled on the MakeHuman body" --makehuman "$tmp/nowhere"
refused "option --resume takes no value" --resume=yes
# Values the API would refuse (or take forever on) only once files are
# written are refused here (the cheap options keep a regression short).
cheap="--levels 1 --instance-frames 2 --test-frames 1 --preroll 0 --size 64x64"
refused "option --levels: expected an integer >= 1 and <= 2147483647, got \"99999999999999999999\"" \
  $cheap --levels 99999999999999999999
refused "option --instance-frames: expected an integer >= 2 and <= 2147483647, got \"3000000000\"" \
  $cheap --instance-frames 3000000000
refused "option --test-frames: expected an integer >= 1 and <= 2147483647" $cheap --test-frames 2147483648
refused "option --newton-cg: expected an integer >= 0 and <= 1000" $cheap --newton-cg 99999999999
refused "option --threads: expected an integer >= 0 and <= 1024, got \"2000\"" $cheap --threads 2000
refused "option --modes: expected an integer >= 1 and <= 1000, got \"1e20\"" $cheap --modes 1e20
refused "option --preroll: expected a number >= 0 and <= 60, got \"61\"" $cheap --preroll 61
refused "option --preroll: expected 0 or a number from 0.001 to 60, got \"0.0001\"" $cheap --preroll 0.0001
refused "option --fps: expected at most the step rate, 120 steps per second by default, got 200; give --step-rate" \
  $cheap --fps 200
refused "option --fps: expected a number >= 1 and <= 100000, got \"1e-320\"" $cheap --fps 1e-320
# Bounds read from multirescloth.limits(), as simulate checks them.
refused "option --fps: expected a number >= 1 and <= 100000, got \"1e6\"" $cheap --fps 1e6
refused "option --step-rate: expected at most 1000 steps per frame \(30000 at --fps 30\)" $cheap --step-rate 1e9
refused "option --waist-smoothing: expected a number >= 0 and <= 1, got \"2\"" --waist-smoothing 2 --makehuman "$tmp"
# The garment bounds --levels (refinement makes at most 2e7 faces) and --modes (clusters of its vertices).
refused "option --levels: 8 uniform refinements of the garment's 760 faces would make 4.98e\+7 faces, .*expected at most 7" \
  $cheap --levels 8
printf 'v 0 0 0\nv 0.5 0 0\nv 0.5 -0.5 0\nv 0 -0.5 0\nf 1 4 3 2\n' > "$tmp/quad.obj"
refused "option --modes: expected at most the high-resolution mesh's 9 vertices \(--levels 1\)" \
  $cheap --garment "$tmp/quad.obj" --modes 10
# An option where a value was expected, an existing file as --out, an empty list entry, a value to a flag.
refused "option --garment needs a value, got the option --levels" $cheap --garment --levels 1
touch "$tmp/afile"
refused "option --out: .*afile exists and is not a folder" $cheap --out "$tmp/afile"
refused "option --out: .*afile exists and is not a folder \(the folder .*afile/out would be in it\)" \
  $cheap --out "$tmp/afile/out"
refused "option --delta: entry 2 of \"5,\" is empty; expected numbers > 0 separated by commas" --delta 5,
# A decimal comma: "5,5" meant 5.5, not delta 5 twice (once merged into one run without a word).
refused "option --delta: 5 is given twice in \"5,5\"; expected distinct numbers > 0 separated by commas, decimals with a point \(5\.5\)" --delta 5,5
refused "option --preroll: expected a number >= 0 and <= [0-9]+ \(one number, decimals with a point: 5\.5\), got \"0,5\"" --preroll 0,5
refused "option --quiet takes no value" --quiet=1
# Broken MakeHuman rig files (JSON) are refused before any work, naming --makehuman.
mkdir -p "$tmp/mh/rigs" "$tmp/mh2/rigs"
: > "$tmp/mh/base.obj" && : > "$tmp/mh2/base.obj"
printf '{"bones": {}, "joints": {}}' > "$tmp/mh/rigs/cmu_mb.mhskel"
printf 'garbage' > "$tmp/mh/rigs/default_weights.mhw"
refused "InputError: pipeline: option --makehuman: .*mh/rigs/default_weights.mhw:1: unexpected .g.; expected a value .*, in a file that should hold MakeHuman skin weights" \
  $cheap --makehuman "$tmp/mh" --units m
printf '{"bones": {"Hips": {"head": "Hips_he' > "$tmp/mh2/rigs/cmu_mb.mhskel"
printf '{"weights": {}}' > "$tmp/mh2/rigs/default_weights.mhw"
refused "InputError: pipeline: option --makehuman: .*mh2/rigs/cmu_mb.mhskel:1: the text ends inside a string.*, in a file that should hold a MakeHuman skeleton" \
  $cheap --makehuman "$tmp/mh2" --units m
printf '{"weights": []}' > "$tmp/mh2/rigs/default_weights.mhw"
printf '{"bones": {}}' > "$tmp/mh2/rigs/cmu_mb.mhskel"
refused "option --makehuman: .*mh2/rigs/cmu_mb.mhskel has no \"joints\" object" $cheap --makehuman "$tmp/mh2" --units m
# A clip in the wrong units (the embedded walks are in metres) is refused
# before any work, with the units that would fit; "auto" is one of the choices.
refused "InputError: pipeline: option --instance: .*walk_instance.bvh read in units 'cm' \(0.01 m per unit\): the figure's legs are 0.01 m long .* expected 0.4-2 times: check the units; in 'm' they are 0.79 m" \
  --motion-units cm
refused "option --motion-units: expected one of m, cmu, dm, cm, mm, inch, auto, got \"feet\"" --motion-units feet
# A garment in the wrong units is refused before any work, with the units that fit.
refused "InputError: pipeline: option --units: .*default_skirt.obj read in 'cm' spans 0.00[0-9]* m .*expected 0.1-4 m for a garment worn by a person: check the units \(in 'm' it spans 0.5[0-9] m\)" \
  --units cm
# An already refined garment (a .om the refinement wrote) is not a coarse one.
printf 'const id = core.loadObject(core.scriptArguments()[0]);\ncore.saveObject(multirescloth.refineUniform(id, 1), core.scriptArguments()[1]);\n' > "$tmp/refine.js"
"$host" -q -b "$tmp/refine.js" -- "$resources/garments/default_skirt.obj" "$tmp/refined.om" ||
  { echo "FAILED: could not write the refined garment"; failed=1; }
refused "InputError: pipeline: option --garment: .*refined.om is already refined \\(its faces reach level 2\\); expected the coarse garment" \
  --garment "$tmp/refined.om"
# A closed surface (a cube of six quads) has no opening to pin as the waist.
printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n' > "$tmp/cube.obj"
refused "InputError: pipeline: option --garment: .*cube.obj is a closed surface \\(no boundary loop\\)" --garment "$tmp/cube.obj"
refused "option --motion-positions: expected one of absolute, relative, got \"local\"" --motion-positions local
# A clip whose pelvis is not called Hips (the embedded new walk, renamed) is
# refused before any work, with its joints and the option that renames them.
sed 's/ROOT Hips/ROOT pelvis/' "$resources/characters/walk_new.bvh" > "$tmp/pelvis_walk.bvh"
refused "InputError: pipeline: option --test: .*pelvis_walk.bvh has no joint 'Hips' \(after renaming\), which the pinned waist follows; its joints: pelvis, LHipJoint, .*give --joint-map FILE.json" \
  --test "$tmp/pelvis_walk.bvh"
printf '{"pelvis": "Hips"' > "$tmp/broken_map.json"
refused "option --joint-map: .*broken_map.json:1: the text ends inside an object; expected .*, in a file that should hold a joint map" --test "$tmp/pelvis_walk.bvh" --joint-map "$tmp/broken_map.json"
# A hand-edited file's stray comma is named by its line and column.
printf '{\n  "pelvis": "Hips",\n}\n' > "$tmp/comma_map.json"
refused "option --joint-map: .*comma_map.json:3: a trailing comma" --test "$tmp/pelvis_walk.bvh" --joint-map "$tmp/comma_map.json"
printf '["pelvis", "Hips"]' > "$tmp/array_map.json"
refused "option --joint-map: .*array_map.json holds an array; expected an object" --joint-map "$tmp/array_map.json"
printf '{"pelvis": 3}' > "$tmp/number_map.json"
refused "option --joint-map: .*number_map.json: \"pelvis\" maps to 3; expected a joint name" --joint-map "$tmp/number_map.json"
printf '{"pelvis": "Hips", "pelvsi": "Hips"}' > "$tmp/typo_map.json"
refused "option --joint-map: .*typo_map.json renames \"pelvsi\", a joint of none of the clips" \
  --test "$tmp/pelvis_walk.bvh" --joint-map "$tmp/typo_map.json"
refused "option --joint-map: no such file" --joint-map "$tmp/no_map.json"
# A map that makes two joints one name is the map's mistake, named with both joints.
printf '{"Hips": "Spine"}' > "$tmp/clash_map.json"
refused "option --joint-map: .*clash_map.json on .*joint renaming: two joints would be named \"Spine\": \"Hips\" \(renamed \"Hips\" -> \"Spine\"\) and \"Spine\" \(kept\)" \
  --joint-map "$tmp/clash_map.json"
# With the map it runs; the embedded instance, which has none of its names,
# is named automatically beside it.
printf '{"pelvis": "Hips"}' > "$tmp/map.json"
n=$((n + 1))
"$host" pipeline -q --out "$tmp/out$n" --test "$tmp/pelvis_walk.bvh" --joint-map "$tmp/map.json" --levels 1 \
  --instance-frames 4 --test-frames 4 --preroll 0.05 --size 64x64 > /dev/null 2> "$tmp/stderr$n" ||
  { echo "FAILED (--joint-map): exit code $?: $(cat "$tmp/stderr$n")"; failed=1; }
grep -q "^### pelvis_walk" "$tmp/out$n/report.md" || { echo "FAILED (--joint-map): no pelvis_walk in the report"; failed=1; }
# An unreadable input (skipped when running as root, who reads everything).
touch "$tmp/locked.obj" && chmod 000 "$tmp/locked.obj"
if ! cat "$tmp/locked.obj" > /dev/null 2>&1; then
  refused "option --garment: cannot read .*locked.obj" --garment "$tmp/locked.obj"
fi
# A garment that is not a quad mesh fails in its loader, naming the file and line, exit 1.
printf 'v 0 0 0\nv 1 0 0\nf 1 2 9\n' > "$tmp/broken.obj"
n=$((n + 1))
"$host" pipeline --garment "$tmp/broken.obj" --out "$tmp/out$n" > /dev/null 2> "$tmp/stderr$n"
code=$?
[ "$code" -eq 1 ] || { echo "FAILED (broken garment): exit code $code"; failed=1; }
grep -q "^\[error\] InputError: .*broken.obj: face 0 (line 3) refers to vertex 9" "$tmp/stderr$n" ||
  { echo "FAILED (broken garment): $(cat "$tmp/stderr$n")"; failed=1; }
grep -q '^    at ' "$tmp/stderr$n" && { echo "FAILED (broken garment): a script stack on stderr"; failed=1; }
# Without its plugins (--plugins naming another folder) the pipeline says so, not a ReferenceError.
n=$((n + 1))
mkdir -p "$tmp/no_plugins"
"$host" --plugins "$tmp/no_plugins" pipeline --out "$tmp/out$n" > /dev/null 2> "$tmp/stderr$n"
code=$?
[ "$code" -eq 1 ] || { echo "FAILED (no plugins): exit code $code"; failed=1; }
grep -q "^\[error\] Error: pipeline: the 'Multires Cloth' and 'Preview' plugins are not loaded" "$tmp/stderr$n" ||
  { echo "FAILED (no plugins): $(cat "$tmp/stderr$n")"; failed=1; }
[ -e "$tmp/out$n" ] && { echo "FAILED (no plugins): its output folder was created"; failed=1; }
# --help prints the options and does nothing else.
"$host" pipeline --help --out "$tmp/help" > "$tmp/help.out" 2>&1 || { echo "FAILED: --help exit code $?"; failed=1; }
grep -q "^Usage: mrcloth pipeline" "$tmp/help.out" || { echo "FAILED: --help text"; failed=1; }
[ -e "$tmp/help" ] && { echo "FAILED: --help created its output folder"; failed=1; }
[ "$failed" -eq 0 ] && echo "pipeline errors: ok ($n cases)"
exit "$failed"
