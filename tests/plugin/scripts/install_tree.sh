#!/bin/sh
# `cmake --install` gives a relocatable tree: the host, its two plugins and
# the resources it runs on, nothing else; moved to another folder, the
# installed host finds its plugins and resources there (not the source
# tree's), runs the pipeline, and MRCLOTH_RESOURCES still overrides.
#
# install_tree.sh <cmake> <build folder> <version> <tmp folder>
set -u
cmake=$1 build=$2 version=$3 tmp=$4
rm -rf "$tmp" && mkdir -p "$tmp" || exit 1
failed=0
fail() { echo "FAILED: $*"; failed=1; }

"$cmake" --install "$build" --prefix "$tmp/first" > "$tmp/install.out" 2>&1 ||
  { cat "$tmp/install.out"; echo "FAILED: cmake --install"; exit 1; }
mv "$tmp/first" "$tmp/moved" || exit 1
prefix="$tmp/moved"
host="$prefix/bin/mrcloth"

# Exactly the host, the two plugins and the three resource folders.
tops=$(cd "$prefix" && find . -mindepth 1 -maxdepth 1 | sort | tr '\n' ' ')
[ "$tops" = "./bin ./lib ./share " ] || fail "install tree's top folders: $tops"
[ "$(ls "$prefix/bin")" = "mrcloth" ] || fail "bin/ holds: $(ls "$prefix/bin")"
plugins=$(find "$prefix/lib" -name '*.so' | sed "s|^$prefix/||" | sort | tr '\n' ' ')
case "$plugins" in
  lib*/mrcloth/plugins/libmrcloth_multirescloth.so\ lib*/mrcloth/plugins/libmrcloth_preview.so\ ) ;;
  *) fail "installed plugins: $plugins" ;;
esac
resources=$(ls "$prefix/share/mrcloth" | tr '\n' ' ')
[ "$resources" = "characters garments scripts " ] || fail "share/mrcloth holds: $resources"
[ -f "$prefix/share/mrcloth/scripts/pipeline.js" ] || fail "no installed pipeline.js"

# The moved host reads its own tree, wherever it is run from.
cat > "$tmp/where.js" <<'JS'
print("resources " + core.resourcePath());
print("plugins " + typeof multirescloth + " " + typeof preview);
const skirt = core.loadObject(core.resourcePath() + "/garments/default_skirt.obj");
print("skirt " + core.objectInfo(skirt).vertices);
JS
(cd / && env -u MRCLOTH_RESOURCES "$host" -q -b "$tmp/where.js") > "$tmp/where.out" 2>&1 ||
  fail "installed host: $(cat "$tmp/where.out")"
grep -qx "resources $prefix/share/mrcloth" "$tmp/where.out" || fail "resourcePath: $(cat "$tmp/where.out")"
grep -qx "plugins object object" "$tmp/where.out" || fail "plugins not loaded: $(cat "$tmp/where.out")"
grep -qx "skirt 800" "$tmp/where.out" || fail "default skirt: $(cat "$tmp/where.out")"
mkdir -p "$tmp/elsewhere" && cp -r "$prefix/share/mrcloth/." "$tmp/elsewhere" || exit 1
MRCLOTH_RESOURCES="$tmp/elsewhere" "$host" -q -b "$tmp/where.js" > "$tmp/override.out" 2>&1
grep -qx "resources $tmp/elsewhere" "$tmp/override.out" || fail "MRCLOTH_RESOURCES ignored: $(cat "$tmp/override.out")"

"$host" --version > "$tmp/version.out" 2>&1 || fail "--version exit code"
grep -q "$version" "$tmp/version.out" || fail "--version: $(cat "$tmp/version.out")"

# The main job from the installed tree (tiny), from another working folder.
(cd "$tmp" && env -u MRCLOTH_RESOURCES "$host" -q pipeline --levels 1 --modes 2 --delta 6,8 --instance-frames 4 \
  --test-frames 2 --preroll 0.1 --size 64x64 --out "$tmp/out") > "$tmp/pipeline.out" 2>&1 ||
  fail "installed pipeline: $(cat "$tmp/pipeline.out")"
grep -q "^pipeline: 8 runs of 4 models" "$tmp/pipeline.out" || fail "pipeline summary: $(cat "$tmp/pipeline.out")"
[ -s "$tmp/out/report.json" ] || fail "installed pipeline wrote no report.json"

[ "$failed" -eq 0 ] && echo "install tree: relocatable, 2 plugins, resources found, pipeline ran"
exit "$failed"
