#!/bin/sh
# The spread of a machine-dependent test (docs/testing.md "Tests that depend on the machine"):
# run one gtest test N times in fresh processes and print, for every number it records with
# RecordProperty, the min, median and max over the runs, and how many runs failed. A bound in
# such a test is set from this spread, with a margin, and the numbers are written beside it.
# Usage: tests/spread.sh PROGRAM FILTER [N] [zink]   e.g.
#   sh tests/spread.sh build/tests/test_render_resources RenderResources.ReusedRendererIsStable 20 zink
set -u
PROG="$1"; FILTER="$2"; N="${3:-20}"; DRIVER="${4:-llvmpipe}"
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
if [ "$DRIVER" = zink ]; then
  export LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=zink
  export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp/xdg-$(id -un)}"
  mkdir -p "$XDG_RUNTIME_DIR" && chmod 700 "$XDG_RUNTIME_DIR"
fi
export LP_NUM_THREADS="${LP_NUM_THREADS:-2}"  # as CTest runs the gl tests
failed=0
i=1
while [ "$i" -le "$N" ]; do
  if ! "$PROG" --gtest_filter="$FILTER" --gtest_output="xml:$T/run$i.xml" >"$T/run$i.log" 2>&1; then
    failed=$((failed + 1)); echo "run $i failed:"; grep -E "Failure|error|FAILED" "$T/run$i.log" | head -5
  fi
  # <property name="NAME" value="NUMBER"/>, one line per property and run
  sed -n 's/.*<property name="\([^"]*\)" value="\(-\{0,1\}[0-9.e+-]*\)".*/\1 \2/p' "$T/run$i.xml" >>"$T/values"
  i=$((i + 1))
done
echo "$FILTER, $N runs${4:+ on $DRIVER}, $failed failed ($(date -u +%Y-%m-%d))"
[ -s "$T/values" ] || { echo "no numeric properties recorded"; exit "$([ "$failed" -eq 0 ] && echo 0 || echo 1)"; }
for name in $(cut -d' ' -f1 "$T/values" | sort -u); do
  awk -v n="$name" '$1 == n { print $2 }' "$T/values" | sort -g |
    awk -v n="$name" '{ v[NR] = $1 } END { printf "  %-40s min %s  median %s  max %s  (%d values)\n", n, v[1], v[int((NR + 1) / 2)], v[NR], NR }'
done
[ "$failed" -eq 0 ]
