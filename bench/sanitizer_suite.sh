#!/usr/bin/env bash
# The whole test suite built with AddressSanitizer and UndefinedBehaviorSanitizer (CPGI_SANITIZE: any
# error aborts the test that met it), as a bench, not in CI: the build and the run take several times the
# ordinary suite's. Prints ctest's summary and the seconds; the log is BUILD_DIR/sanitizer-suite.log.
#   bench/sanitizer_suite.sh [BUILD_DIR] [ctest arguments...]     (default build-asan, all but Fuzz.*)
#   NO_BUILD=1 bench/sanitizer_suite.sh ...     runs the executables as they are built (a rebuild takes hours)
#   TIMEOUT_SCALE=N bench/sanitizer_suite.sh ...   every test's time limit times N (default 5)
set -uo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build-asan}"
shift || true
# Every test's time limit times 5 (600 s → 3000 s for a suite's test): the sanitizers' own slowness, 2–4×,
# on a machine that others share. ctest's --timeout cannot do it, as every test has a TIMEOUT of its own.
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCPGI_SANITIZE=ON \
  -DCPGI_TEST_TIMEOUT_SCALE="${TIMEOUT_SCALE:-5}" -DCPGI_WEB_DIR="${CPGI_WEB_DIR:-$root/build/web}" >/dev/null || exit 1
start=$(date +%s)
if [[ -z "${NO_BUILD:-}" ]]; then
  nice cmake --build "$build" -j2 >"$build/build.log" 2>&1 || { tail -20 "$build/build.log"; exit 1; }
fi
built=$(date +%s)
# detect_leaks: the suite's processes end by exit(); leaks would be reported as errors.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1" UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# Mesa's software driver stays loaded to the end. A process that bakes on GL and terminates its EGL
# display (radiosity/gpu/egl_context.cpp does) lets Mesa dlclose swrast_dri.so, and two 56-byte objects the
# driver callocs and holds only from its own globals (offset 0xb8ec70 in Debian 12's 22.3.6 build) lose
# their root: LeakSanitizer then reports 112 bytes "leaked" at exit, by a frame it cannot name because the
# library is gone (it prints libasan.so+0x38ecb3), so a `leak:swrast_dri.so` suppression never matches it.
# Loaded from the start, the driver is never unloaded and its globals stay roots: no suppression is needed
# and no leak of ours can hide behind one. Its path is found, not assumed; without Mesa nothing is loaded.
# verify_asan_link_order=0: the driver comes before libasan in the load order; it defines no allocator.
mesa_driver=$(ls /usr/lib/*/dri/swrast_dri.so /usr/lib64/dri/swrast_dri.so 2>/dev/null | head -1)
if [[ -n "$mesa_driver" ]]; then
  export LD_PRELOAD="$mesa_driver${LD_PRELOAD:+ $LD_PRELOAD}" ASAN_OPTIONS="$ASAN_OPTIONS:verify_asan_link_order=0"
fi
nice ctest --test-dir "$build" -j2 --output-on-failure -E '^Fuzz\.' "$@" >"$build/sanitizer-suite.log" 2>&1
status=$?
done=$(date +%s)
grep -E "tests passed|tests failed|^\s+[0-9]+ - " "$build/sanitizer-suite.log"
grep -c -E "ERROR: AddressSanitizer|runtime error:" "$build/sanitizer-suite.log" | sed 's/^/sanitizer reports: /'
echo "build $((built - start)) s, suite $((done - built)) s (wall)"
exit $status
