#!/bin/sh
# Builds the libFuzzer targets of the scene loader in build-fuzz/ (clang, ASan + UBSan, coverage)
# and runs each for a bounded time; prints how long each ran clean and how many inputs it tried.
#
# Usage: tests/fuzz/run.sh [SECONDS] [FORMAT...]
#   SECONDS  per target (default 60); FORMAT from: gltf glb json obj ply off stl exr png (all).
# Environment: BUILD (default build-fuzz), NO_BUILD=1 (reuse the built targets), JOBS (ninja -j).
#
# Each target first replays tests/fuzz/corpus/<format>/ and tests/fuzz/regressions/<format>/
# (every input once), then mutates from them. New inputs go to $BUILD/fuzz/<format>/corpus, so
# the committed seeds never change; a failing input is written to $BUILD/fuzz/<format>/ as
# crash-*, leak-*, timeout-* or oom-* and the script exits 1. Keep such an input, after the fix,
# under tests/fuzz/regressions/<format>/ (test_fuzz_replay replays it in every build).
set -eu
cd "$(dirname "$0")/../.."
SRC=$(pwd)
SECS=${1:-60}
[ $# -gt 0 ] && shift
FORMATS=${*:-gltf glb json obj ply off stl exr png}
BUILD=${BUILD:-build-fuzz}

if [ "${NO_BUILD:-0}" != 1 ]; then
  cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang \
    -DCMAKE_CXX_COMPILER=clang++ -DPENUMBRA_FUZZ=ON >/dev/null
  targets=""
  for f in $FORMATS; do targets="$targets fuzz_$f"; done
  # shellcheck disable=SC2086
  ninja -C "$BUILD" -j "${JOBS:-2}" $targets
fi

# Leaks count as failures; UB aborts (the targets are built with -fno-sanitize-recover).
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:detect_leaks=1:allocator_may_return_null=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"

status=0
summary=""
for f in $FORMATS; do
  bin="$BUILD/tests/fuzz/fuzz_$f"
  work="$BUILD/fuzz/$f"
  mkdir -p "$work/corpus"
  seeds="$SRC/tests/fuzz/corpus/$f"
  [ -d "$SRC/tests/fuzz/regressions/$f" ] && seeds="$seeds $SRC/tests/fuzz/regressions/$f"
  case $f in gltf|glb) maxlen=16384 ;; *) maxlen=8192 ;; esac
  # Bounded: -max_total_time for the run, -timeout per input (a hang), -rss_limit_mb and
  # -malloc_limit_mb for memory (an unbounded allocation).
  rc=0
  # shellcheck disable=SC2086
  "$bin" -max_total_time="$SECS" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024 \
    -max_len=$maxlen -print_final_stats=1 -artifact_prefix="$work/" \
    "$work/corpus" $seeds >"$work/log" 2>&1 || rc=$?
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/log" | tail -1)
  speed=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$work/log" | tail -1)
  took=$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$work/log" | tail -1)
  inputs=$(find "$work/corpus" -type f | wc -l)
  if [ $rc -eq 0 ]; then
    line="fuzz_$f: ran ${took:-?} s clean, ${runs:-?} executions (${speed:-?}/s), $inputs new corpus inputs"
  else
    status=1
    artifact=$(sed -n 's/.*Test unit written to \(.*\)$/\1/p' "$work/log" | tail -1)
    line="fuzz_$f: FAILED (exit $rc) after ${runs:-?} executions: ${artifact:-see $work/log}"
    grep -m3 -E "^penumbra fuzz|ERROR: (AddressSanitizer|LeakSanitizer|libFuzzer)|runtime error" \
      "$work/log" || true
  fi
  echo "$line"
  summary="$summary$line
"
done
printf '\n%s' "$summary"
exit $status
