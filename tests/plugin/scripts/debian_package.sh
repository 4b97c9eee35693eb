#!/bin/sh
# cpack's Debian package: the host, its two plugins and the resources under
# /usr, with the shared libraries it needs as dependencies; unpacked into a
# folder, its host runs from there on its own plugins and resources.
# Skipped (77) where Debian's packaging tools are missing.
#
# debian_package.sh <cpack> <build folder> <version> <tmp folder>
set -u
cpack=$1 build=$2 version=$3 tmp=$4
for tool in dpkg-deb dpkg-shlibdeps; do
  command -v "$tool" > /dev/null || { echo "SKIPPED: $tool is not installed (package dpkg-dev)"; exit 77; }
done
rm -rf "$tmp" && mkdir -p "$tmp" || exit 1
failed=0
fail() { echo "FAILED: $*"; failed=1; }

(cd "$tmp" && "$cpack" --config "$build/CPackConfig.cmake" -B "$tmp/out") > "$tmp/cpack.out" 2>&1 ||
  { cat "$tmp/cpack.out"; echo "FAILED: cpack"; exit 1; }
deb=$(ls "$tmp"/out/*.deb 2>/dev/null)
[ "$(basename "$deb")" = "mrcloth_${version}_amd64.deb" ] || { echo "FAILED: package file: $deb"; exit 1; }

[ "$(dpkg-deb -f "$deb" Package)" = "mrcloth" ] || fail "Package: $(dpkg-deb -f "$deb" Package)"
[ "$(dpkg-deb -f "$deb" Version)" = "$version" ] || fail "Version: $(dpkg-deb -f "$deb" Version)"
depends=$(dpkg-deb -f "$deb" Depends)
for needed in libopenmesh1 libqt6core6 libqt6gui6 libqt6qml6 libc6 libstdc++6; do
  case "$depends" in *"$needed "*) ;; *) fail "Depends lacks $needed: $depends" ;; esac
done
# Exactly the host, the plugins and the resources, under /usr.
files=$(dpkg-deb -c "$deb" | awk '$1 !~ /^d/ {print $NF}' | sort | tr '\n' ' ')
expected="./usr/bin/mrcloth ./usr/lib/mrcloth/plugins/libmrcloth_multirescloth.so ./usr/lib/mrcloth/plugins/libmrcloth_preview.so"
case "$files" in
  "$expected ./usr/share/mrcloth/"*) ;;
  *) fail "package files: $files" ;;
esac
for resource in scripts/pipeline.js garments/default_skirt.obj characters/walk_new.bvh; do
  case "$files" in *"./usr/share/mrcloth/$resource "*) ;; *) fail "package lacks share/mrcloth/$resource" ;; esac
done

# Unpacked anywhere, the host runs on its own tree (the package's prefix,
# CPACK_PACKAGING_INSTALL_PREFIX, inside the folder it is unpacked into).
dpkg-deb -x "$deb" "$tmp/unpacked_tree" || { echo "FAILED: dpkg-deb -x"; exit 1; }
host="bin/mrcloth"  # the host's place in the install tree, below the prefix
prefix=$(dpkg-deb -c "$deb" | awk -v host="$host" '{ n = $NF; k = length(n) - length(host)
  if (k > 0 && substr(n, k + 1) == host) print substr(n, 3, k - 3) }')
unpacked="$tmp/unpacked_tree/$prefix"
[ -x "$unpacked/bin/mrcloth" ] || { echo "FAILED: no host in the unpacked package ($unpacked)"; exit 1; }
cat > "$tmp/where.js" <<'JS'
print("resources " + core.resourcePath());
print("plugins " + typeof multirescloth + " " + typeof preview);
print("skirt " + core.objectInfo(core.loadObject(core.resourcePath() + "/garments/default_skirt.obj")).vertices);
JS
(cd / && env -u MRCLOTH_RESOURCES "$unpacked/bin/mrcloth" -q -b "$tmp/where.js") > "$tmp/where.out" 2>&1 ||
  fail "unpacked host: $(cat "$tmp/where.out")"
grep -qx "resources $unpacked/share/mrcloth" "$tmp/where.out" || fail "resourcePath: $(cat "$tmp/where.out")"
grep -qx "plugins object object" "$tmp/where.out" || fail "plugins: $(cat "$tmp/where.out")"
grep -qx "skirt 800" "$tmp/where.out" || fail "default skirt: $(cat "$tmp/where.out")"

[ "$failed" -eq 0 ] && echo "debian package: $(basename "$deb"), Depends: $depends"
exit "$failed"
