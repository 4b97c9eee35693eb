#!/bin/sh
# In a locale with a decimal comma (Qt sets the C library's from the
# user's), the numbers in messages keep their point: the libraries' printf
# said "1,98 m" beside "0.4-2 times" in de_DE. Skipped where the machine
# has no such locale (locale-gen de_DE.UTF-8 makes one).
#
# decimal_comma_locale.sh <mrcloth> <resources> <tmp folder>
set -u
host=$1 resources=$2 tmp=$3
locale=$(locale -a 2>/dev/null | grep -i -m1 -E '^(de_DE|fr_FR)\.utf-?8$')
[ -n "$locale" ] || { echo "SKIP: no de_DE or fr_FR UTF-8 locale on this machine"; exit 77; }
rm -rf "$tmp" && mkdir -p "$tmp" || exit 1
cat > "$tmp/messages.js" <<JS
try {
  multirescloth.motionInfo({path: "$resources/characters/walk_new.bvh", scale: 2.5});
} catch (e) { print(e.message); }
JS
LC_ALL=$locale "$host" -q -b "$tmp/messages.js" > "$tmp/out.txt" 2>&1
if grep -q 'legs are 1\.98 m long' "$tmp/out.txt" && grep -q '2\.5 times an adult.s 0\.79 m' "$tmp/out.txt"; then
  echo "decimal points in $locale: ok"
  exit 0
fi
echo "in $locale the message lost its decimal points:"; cat "$tmp/out.txt"
exit 1
