#!/usr/bin/env bash
# Installs mrcloth's build and test dependencies from Debian 12 packages.
# Idempotent: packages already present are not reinstalled and apt is not
# touched at all when everything is there. Works as root or through sudo.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libopenmesh-dev       # mesh data structure and IO (OBJ/OFF/PLY/OM)
  libeigen3-dev         # dense and sparse linear algebra
  libcgal-dev           # robust geometry (planar convex hulls)
  qt6-base-dev          # Qt Core/Gui: plugin system, offscreen images
  qt6-declarative-dev   # QJSEngine: the scripting host
  libgtest-dev          # unit tests
  libbenchmark-dev      # micro-benchmarks
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all packages present"
  exit 0
fi

if [[ $(id -u) -eq 0 ]]; then sudo_cmd=(); else sudo_cmd=(sudo); fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
