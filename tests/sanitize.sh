#!/bin/sh
# ASan + UBSan: configure build-asan/ with PENUMBRA_SANITIZE=ON, build it, run the whole CTest
# suite under the sanitizers. Any sanitizer report fails the test it happens in (halt on error,
# UB is not recoverable). Leak checking is on; tests/lsan.supp suppresses only leaks whose stack
# is inside Mesa / LLVM / libEGL / llvmpipe system libraries, never penumbra code.
# Usage: tests/sanitize.sh [extra ctest args...]   (from anywhere; BUILD=dir overrides build-asan)
set -eu
cd "$(dirname "$0")/.."
SRC=$(pwd)
BUILD=${BUILD:-build-asan}
start=$(date +%s)
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPENUMBRA_SANITIZE=ON >/dev/null
cmake --build "$BUILD"
built=$(date +%s)
# detect_leaks: on. The GL driver (llvmpipe) is not instrumented; its own allocations are covered
# by the suppression file. abort_on_error keeps the exit non-zero for CTest.
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:detect_leaks=1:strict_init_order=1:check_initialization_order=1:print_summary=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:print_summary=1"
export LSAN_OPTIONS="suppressions=$SRC/tests/lsan.supp:print_suppressions=0"
rc=0
LOG="$BUILD/sanitize-ctest.log"
{ ctest --test-dir "$BUILD" --output-on-failure -j2 "$@"; echo "ctest-exit $?"; } 2>&1 | tee "$LOG"
rc=$(sed -n 's/^ctest-exit //p' "$LOG")
# LeakSanitizer's own tracer can crash at process exit ("Tracer caught signal 11", "LeakSanitizer
# has encountered a fatal error") while the GL driver's worker threads are being torn down: a
# test that passed, then a sanitizer-internal failure (2026-12-02: twice in the full -j2 suite,
# both times Scenes/MultiViewVsRaytrace...15_two_plates_mvr; alone 1 of 5 runs). While every
# failed test is one of those, the failed ones run again, at most 3 times; any other failure
# stands.
FAILED="$BUILD/Testing/Temporary/LastTestsFailed.log"
tries=0
while [ "$rc" -ne 0 ] && [ -f "$FAILED" ] && [ "$tries" -lt 3 ]; do
  failed=$(wc -l < "$FAILED")
  tracer=$(grep -c "LeakSanitizer has encountered a fatal error" "$LOG" || true)
  [ "$tracer" -ge "$failed" ] || break
  tries=$((tries + 1))
  echo "sanitize.sh: $failed failed test(s), all with LeakSanitizer's tracer crash at exit: rerun $tries of 3"
  { ctest --test-dir "$BUILD" --output-on-failure --rerun-failed; echo "ctest-exit $?"; } 2>&1 | tee "$LOG"
  rc=$(sed -n 's/^ctest-exit //p' "$LOG")
done
end=$(date +%s)
echo "sanitize.sh: build $((built - start)) s, tests $((end - built)) s, exit $rc"
exit $rc
