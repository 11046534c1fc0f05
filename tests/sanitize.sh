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
ctest --test-dir "$BUILD" --output-on-failure -j2 "$@" || rc=$?
end=$(date +%s)
echo "sanitize.sh: build $((built - start)) s, tests $((end - built)) s, exit $rc"
exit $rc
