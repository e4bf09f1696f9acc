#!/usr/bin/env bash
# Installs the Debian 12 packages cpgi needs (only the missing ones) and builds it (Release) into build/.
#   ./setup.sh               install + configure + build
#   BUILD_DIR=build-asan CPGI_CMAKE_ARGS="-DCPGI_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo" ./setup.sh
#   CPGI_CMAKE_ARGS="-DCPGI_BENCHMARKS=ON" ./setup.sh
set -euo pipefail
cd "$(dirname "$0")"

packages=(
  build-essential cmake ninja-build pkg-config
  libopenvdb-dev libboost-iostreams-dev libcgal-dev libglm-dev
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
  libopenexr-dev libtinygltf-dev libtinyobjloader-dev nlohmann-json3-dev libstb-dev
  libembree-dev libtbb-dev libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

build_dir="${BUILD_DIR:-build}"
# shellcheck disable=SC2086
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release ${CPGI_CMAKE_ARGS:-} >/dev/null
cmake --build "$build_dir" -j "$(nproc)"
