#!/bin/sh
# The C++ is formatted by .clang-format (clang-format 14, Debian's): every tracked .cpp, .h and
# .hpp but the headers C++ and GLSL share (src/shared/*.h and every shaders/ folder's), whose
# GLSL subset the formatter does not know. Run by .ci/run; `sh tests/format_test.sh --fix`
# formats in place. Usage: format_test.sh [--fix] (from anywhere in the tree).
set -u
cd "$(git rev-parse --show-toplevel)" || exit 1
command -v clang-format >/dev/null || { echo "format: clang-format is not installed (./setup.sh --deps)"; exit 1; }
files=$(git ls-files '*.cpp' '*.h' '*.hpp' | grep -v -e '/shaders/' -e '^src/shared/[^/]*\.h$' -e '^tests/fuzz/corpus/')
if [ "${1:-}" = --fix ]; then
  # shellcheck disable=SC2086
  exec clang-format -i $files
fi
# shellcheck disable=SC2086
if ! clang-format --dry-run --Werror $files 2>"${TMPDIR:-/tmp}/penumbra-format.log"; then
  grep -c "error:" "${TMPDIR:-/tmp}/penumbra-format.log" | sed 's/^/format: lines to change: /'
  grep "error:" "${TMPDIR:-/tmp}/penumbra-format.log" | head -20
  echo "format: FAIL: run sh tests/format_test.sh --fix"
  exit 1
fi
echo "format: $(echo "$files" | wc -l) files as .clang-format says"
