#!/bin/sh
# The tables the docs take from the code are the code's: README's technique table (between
# <!-- technique-table:begin --> and <!-- technique-table:end -->) is `penumbra list --format
# markdown`, docs/cli.md's parameter table (<!-- technique-params:... -->) is `penumbra list
# --params --format markdown`, and each technique folder's README.md has both for its own rows. And README stays the front door: under 300 lines, linking every
# page of docs/. Usage: generated_tables_test.sh PENUMBRA SRCDIR [--write]; --write pastes the
# generated tables between their markers instead of comparing.
P="$1"; SRC="$2"; WRITE="${3:-}"; T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
fail=0
# between FILE MARKER: the lines between the marker pair in FILE.
between() { sed -n "/^<!-- $2:begin -->\$/,/^<!-- $2:end -->\$/p" "$1" | sed '1d;$d'; }
check() {  # check FILE MARKER COMMAND...
  file=$1; marker=$2; shift 2
  "$@" >"$T/generated" || { echo "FAIL: $*"; fail=1; return; }
  if [ "$WRITE" = --write ]; then
    awk -v b="<!-- $marker:begin -->" -v e="<!-- $marker:end -->" -v g="$T/generated" '
      $0 == b { print; while ((getline line < g) > 0) print line; skip = 1; next }
      $0 == e { skip = 0 }
      !skip' "$SRC/$file" >"$T/rewritten" && cat "$T/rewritten" >"$SRC/$file"
  fi
  between "$SRC/$file" "$marker" >"$T/written"
  test -s "$T/written" || { echo "FAIL: $file has no $marker table between its markers"; fail=1; return; }
  if ! diff -u "$T/written" "$T/generated"; then
    echo "FAIL: $file's $marker table differs from \`$*\` (above: - written, + generated); paste its output between the markers (or run this script with --write)"
    fail=1
  fi
}
check README.md technique-table "$P" list --format markdown
check docs/cli.md technique-params "$P" list --params --format markdown
# Each technique folder's README.md: its rows (named on its "<!-- techniques: ... -->" line) and
# their parameters; every row of the table in exactly one folder's README.
: >"$T/foldered"
for readme in "$SRC"/src/techniques/*/README.md; do
  folder=${readme#"$SRC"/}
  names=$(sed -n 's/^<!-- techniques: \(.*\) -->$/\1/p' "$readme")
  [ -n "$names" ] || { echo "FAIL: $folder names no techniques (<!-- techniques: ... -->)"; fail=1; continue; }
  # shellcheck disable=SC2086
  check "$folder" technique-table "$P" list --format markdown $names
  # shellcheck disable=SC2086
  check "$folder" technique-params "$P" list --params --format markdown $names
  printf '%s\n' $names >>"$T/foldered"
done
"$P" list --json | sed -n 's/^ *"name": "\(.*\)",*$/\1/p' | sort >"$T/all"
sort "$T/foldered" >"$T/foldered.sorted"
if ! diff -u "$T/all" "$T/foldered.sorted"; then
  echo "FAIL: the technique folders' READMEs do not name every technique exactly once (above: - table, + READMEs)"
  fail=1
fi
# Every technique is listed with its parameters.
"$P" list --params >"$T/text" || exit 1
for t in dcs dcs-lut mvr vwss reproject pcss-minfilter vssm; do
  grep -q "^$t " "$T/text" || { echo "FAIL: list --params lacks $t"; fail=1; }
done
grep -q "^    coverage  *exact  *exact|naive|lut" "$T/text" || { echo "FAIL: list --params lacks dcs's coverage"; fail=1; }
lines=$(wc -l <"$SRC/README.md")
[ "$lines" -lt 300 ] || { echo "FAIL: README.md has $lines lines (the front door stays under 300: the rest goes to docs/)"; fail=1; }
for page in $(cd "$SRC" && find docs -name '*.md' | sort); do
  grep -q "($page)" "$SRC/README.md" || grep -q "($page#" "$SRC/README.md" ||
    { echo "FAIL: README.md does not link $page"; fail=1; }
done
[ $fail -eq 0 ] && echo "README's technique table, docs/cli.md's parameter table and the technique folders' tables equal the code's; README is $lines lines and links every page of docs/"
exit $fail
