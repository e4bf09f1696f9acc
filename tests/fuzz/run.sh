#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, -fsanitize=fuzzer,address,undefined) into build-fuzz and runs each
# for a bounded time, one after the other. A crash, leak, timeout or out-of-memory input is kept under
# tests/fuzz/regressions/<target>/, which the ordinary suite replays (FuzzRegressions.<target>).
#   tests/fuzz/run.sh                 every target, 60 s each
#   tests/fuzz/run.sh 300 glb obj     those targets, 300 s each
# Seeds: the seed scenes as .glb and .gltf (made with build/apps/cpgi when it exists) and
# tests/fuzz/seeds/<target>/. The corpus grows in build-fuzz/corpus/<target>/ across runs.
set -uo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
seconds="${1:-60}"
shift || true
targets=("$@")
((${#targets[@]})) || targets=(gltf glb obj scene_checks exr texture)
build="${BUILD_DIR:-$root/build-fuzz}"
main_build="${CPGI_BUILD_DIR:-$root/build}"  # the ordinary build: its cpgi makes seeds, its web/ configures

command -v clang++ >/dev/null || { echo "run.sh: clang++ and libFuzzer are needed (apt install clang libclang-rt-14-dev)" >&2; exit 1; }
# The whole tree configures, report.html's writer too: it takes the npm packages ./setup.sh put in build/web.
# -O1 -gline-tables-only as OSS-Fuzz builds: the sanitizers' reports keep their file:line stacks, and
# contact_cuts.cpp (CGAL), the longest object of this build, compiles in 46 CPU seconds against 57 at
# RelWithDebInfo's -O2 -g (NDEBUG kept: the same checks as the product's).
# ccache, when there is one, keeps the objects from one run to the next.
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
flags="-O1 -gline-tables-only -DNDEBUG"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCPGI_FUZZ=ON \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="$flags" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$flags" "${launcher[@]}" \
  -DCPGI_WEB_DIR="$main_build/web" >/dev/null || exit 1
nice cmake --build "$build" -j2 -t $(printf 'fuzz_%s ' "${targets[@]}") >/dev/null || exit 1

cpgi="$main_build/apps/cpgi"
failed=0
for target in "${targets[@]}"; do
  corpus="$build/corpus/$target"
  regressions="$root/tests/fuzz/regressions/$target"
  mkdir -p "$corpus" "$regressions"
  if [[ -x "$cpgi" && ( "$target" == glb || "$target" == gltf ) ]]; then
    for seed in seed1 seed2 seed3; do
      [[ -e "$corpus/$seed.$target" ]] || "$cpgi" generate "$seed" -o "$corpus/$seed.$target" >/dev/null
    done
  fi
  [[ -d "$root/tests/fuzz/seeds/$target" ]] && cp -n "$root/tests/fuzz/seeds/$target"/* "$corpus/" 2>/dev/null
  if [[ "$target" == scene_checks && -z "$(ls -A "$corpus")" ]]; then
    for i in 1 2 3 4; do head -c 256 /dev/urandom >"$corpus/random$i"; done
  fi
  echo "== $target: ${seconds} s"
  nice "$build/tests/fuzz/fuzz_$target" "$corpus" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2560 \
    -max_len=1048576 -print_final_stats=1 -artifact_prefix="$regressions/" 2>&1 |
    grep -E '^#[0-9]+[[:space:]]+(DONE|INITED)|^stat::(number_of_executed_units|peak_rss_mb)|ERROR|SUMMARY|Test unit written'
  status=${PIPESTATUS[0]}
  ((status == 0)) || { echo "== $target: FOUND A PROBLEM (exit $status), input kept in $regressions"; failed=1; }
done
exit $failed
