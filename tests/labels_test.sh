#!/bin/sh
# Every CTest test says what it needs (tests/CMakeLists.txt "Labels"): exactly one of cpu and
# gl, and the sets CI runs are not empty. Usage: labels_test.sh BUILD_DIR
B="$1"; fail=0
count() { ctest --test-dir "$B" -N "$@" | sed -n 's/^Total Tests: //p'; }
none=$(count -LE '^(cpu|gl)$')
both=$(count -L '^cpu$' -L '^gl$')
[ "$none" = 0 ] || { echo "FAIL: $none test(s) labelled neither cpu nor gl:"; ctest --test-dir "$B" -N -LE '^(cpu|gl)$'; fail=1; }
[ "$both" = 0 ] || { echo "FAIL: $both test(s) labelled both cpu and gl"; fail=1; }
# browser, llvmpipe and sanitize are kinds of gl test here.
for label in browser llvmpipe sanitize; do
  n=$(count -L "^$label\$" -LE '^gl$')
  [ "$n" = 0 ] || { echo "FAIL: $n test(s) labelled $label without gl"; fail=1; }
done
for label in cpu gl sanitize slow browser llvmpipe; do
  n=$(count -L "^$label\$")
  echo "$label: ${n:-?} tests"
  [ "${n:-0}" -gt 0 ] || { echo "FAIL: no test labelled $label"; fail=1; }
done
exit $fail
