#!/usr/bin/env bash
# Installs the Debian 12 packages cpgi needs (only the missing ones) and builds it (Release) into build/.
#   ./setup.sh               install + configure + build the `cpgi` tool alone (what a bake needs)
#   ./setup.sh --tests       the same, then every target: the test suites, cpgi-dask's test, the examples
#   BUILD_DIR=build-asan CPGI_CMAKE_ARGS="-DCPGI_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo" ./setup.sh
#   CPGI_CMAKE_ARGS="-DCPGI_BENCHMARKS=ON" ./setup.sh
set -euo pipefail
cd "$(dirname "$0")"

targets=(--target cpgi)
case "${1:-}" in
  "") ;;
  --tests) targets=() ;;
  *) echo "setup.sh: unknown option '$1' (./setup.sh, or ./setup.sh --tests to build the tests too)" >&2; exit 1 ;;
esac

packages=(
  build-essential cmake ninja-build pkg-config
  libopenvdb-dev libboost-iostreams-dev libcgal-dev libglm-dev
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
  libopenexr-dev libtinygltf-dev libtinyobjloader-dev nlohmann-json3-dev libstb-dev
  libpng-dev libjpeg62-turbo-dev
  libembree-dev libtbb-dev libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev
  clang libclang-rt-14-dev
  chromium
  python3-distributed
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# node and npm (report.html's three.js, the glTF validator, the browser test): Debian's, unless a node
# that brings its own npm is there already (NodeSource's nodejs, which conflicts with Debian's npm).
command -v node >/dev/null && command -v npm >/dev/null || missing+=(nodejs npm)
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

build_dir="${BUILD_DIR:-build}"
# The npm packages of core/html_report/web/package-lock.json, into the build folder (never into the
# sources); again only when the lock file changed since the last install that succeeded.
web_dir="$build_dir/web"
if ! cmp -s core/html_report/web/package-lock.json "$web_dir/installed-lock.json"; then
  echo "setup: npm ci into $web_dir"
  mkdir -p "$web_dir"
  cp core/html_report/web/package.json core/html_report/web/package-lock.json "$web_dir/"
  (cd "$web_dir" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
  cp core/html_report/web/package-lock.json "$web_dir/installed-lock.json"
fi
# shellcheck disable=SC2086
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release ${CPGI_CMAKE_ARGS:-} >/dev/null
# The main job needs the `cpgi` target only (report.html's viewer is compiled into it): 145 build steps,
# 9.4 CPU minutes, where every target with the tests took 23 (issue 50); the rest waits for --tests.
cmake --build "$build_dir" -j "$(nproc)" "${targets[@]}"
