#!/usr/bin/env bash
# The whole test suite built with AddressSanitizer and UndefinedBehaviorSanitizer (CPGI_SANITIZE: any
# error aborts the test that met it), as a bench, not in CI: the build and the run take several times the
# ordinary suite's. Prints ctest's summary and the seconds; the log is BUILD_DIR/sanitizer-suite.log.
#   bench/sanitizer_suite.sh [BUILD_DIR] [ctest arguments...]     (default build-asan, all but Fuzz.*)
set -uo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build-asan}"
shift || true
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCPGI_SANITIZE=ON \
  -DCPGI_WEB_DIR="${CPGI_WEB_DIR:-$root/build/web}" >/dev/null || exit 1
start=$(date +%s)
nice cmake --build "$build" -j2 >"$build/build.log" 2>&1 || { tail -20 "$build/build.log"; exit 1; }
built=$(date +%s)
# detect_leaks: the suite's processes end by exit(); leaks would be reported as errors.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1" UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
nice ctest --test-dir "$build" -j2 --output-on-failure --timeout 3000 -E '^Fuzz\.' "$@" >"$build/sanitizer-suite.log" 2>&1
status=$?
done=$(date +%s)
grep -E "tests passed|tests failed|^\s+[0-9]+ - " "$build/sanitizer-suite.log"
grep -c -E "ERROR: AddressSanitizer|runtime error:" "$build/sanitizer-suite.log" | sed 's/^/sanitizer reports: /'
echo "build $((built - start)) s, suite $((done - built)) s (wall)"
exit $status
