#!/bin/sh
# ASan + UBSan: configure build-asan/ with PENUMBRA_SANITIZE=ON, build the programs the tests
# run (target penumbra_test_programs: not the standalone bench binaries), run every cpu test and
# the sanitize-labelled gl tests (tests/CMakeLists.txt "Labels") under the sanitizers. Any sanitizer report fails the test it happens in (halt on error,
# UB is not recoverable). Leak checking is on; tests/lsan.supp suppresses only leaks whose stack
# is inside Mesa / LLVM / libEGL / llvmpipe system libraries, never penumbra code.
# Usage: tests/sanitize.sh [extra ctest args...]   (from anywhere; BUILD=dir overrides build-asan)
# Extra -L / -R arguments narrow the labelled set further (ctest ANDs its -L options).
set -eu
cd "$(dirname "$0")/.."
SRC=$(pwd)
BUILD=${BUILD:-build-asan}
start=$(date +%s)
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPENUMBRA_SANITIZE=ON >/dev/null
cmake --build "$BUILD" --target penumbra_test_programs
built=$(date +%s)
# detect_leaks: on. The GL driver (llvmpipe) is not instrumented; its own allocations are covered
# by the suppression file. abort_on_error keeps the exit non-zero for CTest.
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:detect_leaks=1:strict_init_order=1:check_initialization_order=1:print_summary=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:print_summary=1"
export LSAN_OPTIONS="suppressions=$SRC/tests/lsan.supp:print_suppressions=0"
LOG="$BUILD/sanitize-ctest.log"
# ctest's exit code through the pipe into tee: `if` so that set -e does not end the group before
# the code is written (it did: an empty code, and the script exited 0 after failed tests).
runCtest() {
  { if ctest --test-dir "$BUILD" --output-on-failure "$@"; then echo "ctest-exit 0"; else echo "ctest-exit $?"; fi; } 2>&1 | tee "$LOG"
  rc=$(sed -n 's/^ctest-exit //p' "$LOG")
  rc=${rc:-1}
}
runCtest -j2 -L '^(cpu|sanitize)$' "$@"
# LeakSanitizer's own tracer can crash at process exit ("Tracer caught signal 11", "LeakSanitizer
# has encountered a fatal error") while the GL driver's worker threads are being torn down: a
# test that passed, then a sanitizer-internal failure (2026-12-02: twice in the full -j2 suite,
# both times Scenes/MultiViewVsRaytrace...15_two_plates_mvr; alone 1 of 5 runs). While every
# failed test is one of those, the failed ones run again, at most twice; a test whose tracer
# still crashes (MultiView.VwssSplitsPointsThatExceedOneStorageBlock, which fills 128 MiB
# storage blocks, did so in 3 of 3 runs on 2026-12-02) runs a last time under ASan and UBSan
# with leak checking off, and the script names it. Any other failure stands.
FAILED="$BUILD/Testing/Temporary/LastTestsFailed.log"
tracerOnly() {
  [ "$rc" -ne 0 ] && [ -f "$FAILED" ] || return 1
  failed=$(wc -l < "$FAILED")
  tracer=$(grep -c "LeakSanitizer has encountered a fatal error" "$LOG" || true)
  [ "$tracer" -ge "$failed" ]
}
tries=0
while tracerOnly && [ "$tries" -lt 2 ]; do
  tries=$((tries + 1))
  echo "sanitize.sh: $failed failed test(s), all with LeakSanitizer's tracer crash at exit: rerun $tries of 2"
  runCtest --rerun-failed
done
if tracerOnly; then
  echo "sanitize.sh: LeakSanitizer's tracer crashed again in: $(sed 's/^[0-9]*://' "$FAILED" | tr '\n' ' ')"
  echo "sanitize.sh: those run once more under ASan + UBSan without leak checking"
  ASAN_OPTIONS=$(echo "$ASAN_OPTIONS" | sed 's/detect_leaks=1/detect_leaks=0/')
  export ASAN_OPTIONS
  runCtest --rerun-failed
fi
end=$(date +%s)
echo "sanitize.sh: build $((built - start)) s, tests $((end - built)) s, exit $rc"
exit $rc
