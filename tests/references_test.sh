#!/bin/sh
# Citations resolve, and the product names no issue numbers. Every "<KEY> paper" in the code,
# shaders, tests, benchmarks, scenes and docs is a key of docs/references.md, and every
# "<Name> et al. <year>" / "<Name> and <Name> <year>" has a row there naming that author and
# year. No "issue <n>" anywhere in them: an issue number resolves nowhere in the repository
# (say what and why instead). Usage: references_test.sh SRCDIR
SRC="$1"; T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
REFS="$SRC/docs/references.md"
test -s "$REFS" || { echo "FAIL: docs/references.md is missing"; exit 1; }
cd "$SRC" || exit 1
files() {
  find src geometry shaders tests bench scenes docs cmake luts .ci CMakeLists.txt README.md CODE_STYLE.md setup.sh \
    -type f \( -name '*.cpp' -o -name '*.h' -o -name '*.hpp' -o -name '*.glsl' -o -name '*.vert' -o -name '*.frag' \
    -o -name '*.geom' -o -name '*.comp' -o -name '*.md' -o -name '*.json' -o -name '*.sh' -o -name '*.cmake' \
    -o -name '*.txt' -o -name '*.py' -o -name run \) 2>/dev/null | grep -v '^tests/fuzz/corpus/\|^tests/fuzz/regressions/'
}
files >"$T/files"
fail=0
# The keys: the first column of the table.
sed -n 's/^| \([A-Za-z][A-Za-z0-9-]*\) | .*/\1/p' "$REFS" | grep -v '^key$' >"$T/keys"
xargs grep -ohE '\b[A-Z][A-Z0-9-]+ paper\b' <"$T/files" | sed 's/ paper$//' | sort -u >"$T/cited"
# ... and every link to references.md whose text is a key.
xargs grep -ohE '\[[A-Z][A-Za-z0-9-]*\]\([./a-z]*references\.md\)' <"$T/files" | sed 's/^\[\([^]]*\)\].*/\1/' >>"$T/cited"
sort -u -o "$T/cited" "$T/cited"
while read -r key; do
  grep -qx -- "$key" "$T/keys" || { echo "FAIL: '$key' is cited, but docs/references.md has no key $key"; fail=1; }
done <"$T/cited"
xargs grep -ohE "[A-Z][A-Za-z'-]+ (et al\.?|and [A-Z][A-Za-z'-]+) \(?(19|20)[0-9]{2}" <"$T/files" | sort -u >"$T/authors"
while read -r cite; do
  year=$(printf '%s' "$cite" | grep -oE '(19|20)[0-9]{2}$')
  case "$cite" in
    *" et al"*) name=${cite%% et al*} ;;
    *) name=$(printf '%s' "$cite" | sed -E 's/.* and ([^ ]+) \(?[0-9]{4}$/\1/') ;;
  esac
  grep '^| ' "$REFS" | grep -F -- "$name" | grep -q -- "$year" ||
    { echo "FAIL: '$cite' is cited, but no row of docs/references.md names $name and $year"; fail=1; }
done <"$T/authors"
if xargs grep -nHiE '\bissues? #?[0-9]+' <"$T/files" >"$T/issues"; then
  echo "FAIL: issue numbers in the product (say what and why instead):"; cat "$T/issues"; fail=1
fi
[ $fail -eq 0 ] && echo "$(wc -l <"$T/cited") paper keys and $(wc -l <"$T/authors") author-year citations resolve; no issue numbers"
exit $fail
