#!/bin/sh
# README's table of technique parameters is the declarations': the lines between
# <!-- technique-params:begin --> and <!-- technique-params:end --> in README.md equal
# `penumbra list --params --format markdown`. Usage: params_readme_test.sh PENUMBRA SRCDIR
P="$1"; SRC="$2"; T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
"$P" list --params --format markdown >"$T/declared" || { echo "FAIL: list --params --format markdown"; exit 1; }
sed -n '/^<!-- technique-params:begin -->$/,/^<!-- technique-params:end -->$/p' "$SRC/README.md" | sed '1d;$d' >"$T/readme"
test -s "$T/readme" || { echo "FAIL: README.md has no technique-params markers"; exit 1; }
if ! diff -u "$T/readme" "$T/declared"; then
  echo "FAIL: README's parameter table differs from the declarations (above: - README, + declared);"
  echo "      paste \`penumbra list --params --format markdown\` between the markers"
  exit 1
fi
# Every technique of the table is listed with its parameters.
"$P" list --params >"$T/text" || exit 1
for t in dcs dcs-lut mvr vwss reproject pcss-minfilter vssm; do
  grep -q "^$t " "$T/text" || { echo "FAIL: list --params lacks $t"; exit 1; }
done
grep -q "^    coverage  *exact  *exact|naive|lut" "$T/text" || { echo "FAIL: list --params lacks dcs's coverage"; cat "$T/text"; exit 1; }
echo "README's parameter table equals the declarations"
