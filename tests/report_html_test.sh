#!/bin/sh
# The HTML report in headless Chromium: `compare` with a sweep and --frames
# writes index.html; Chromium loads it from disk (no network), every image loads (the page's own
# check sets data-images="loaded/total"), the plot has a point per plotted run, every point has
# its label (a <text> with the technique's name, shown or on hover), no colour is shared by two
# families, FLIP is in the table and the JSON, and the console stays empty (no script errors).
# Then the default scene with every technique: the labels the page shows by default do not
# overlap (its script measures them). Usage: report_html_test.sh PENUMBRA SRCDIR PART, PART
# sweep (the first report) or default (the default scene): one CTest test each.
# Exits 77 (skipped) without a GL context or without chromium (setup.sh installs it).
P="$1"; SRC="$2"; PART="$3"; T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
CHROMIUM=$(command -v chromium || command -v chromium-browser || true)
[ -n "$CHROMIUM" ] || { echo "chromium not installed (setup.sh installs it): skipped"; exit 77; }
fail=0
# The sweep report: a sweep, frames, FLIP, every image loaded, a broken page caught.
sweep() {
  "$P" compare "$SRC/scenes/spinning-fan.json" -W 64 -H 64 --techniques hard-sv,mvr,pcss \
    --sweep samples=4,8 --param map=128 --frames 2 --timing-frames 1 --warmup 0 -o "$T/out" 2>"$T/err"
  rc=$?
  if [ "$rc" -eq 77 ] || grep -q "no GL context\|cannot create.*context" "$T/err"; then cat "$T/err"; exit 77; fi
  [ "$rc" -eq 0 ] || { echo "FAIL: compare exit $rc"; cat "$T/err"; exit 1; }
  for f in index.html report.json report.csv table.txt plot.svg raytrace__samples-4.png mvr__samples-8_heat.png \
    mvr__samples-8_flip.png; do
    test -s "$T/out/$f" || { echo "FAIL: compare did not write $f"; fail=1; }
  done
  # 2 presets x (raytrace + 3 techniques) = 8 runs, all plotted (the converged reference gives
  # the same-sample references an error too).
  rows=$(($(wc -l < "$T/out/report.csv") - 1))
  [ "$rows" -eq 8 ] || { echo "FAIL: report.csv has $rows runs, want 8"; fail=1; }
  grep -q '"flicker"' "$T/out/report.json" || { echo "FAIL: report.json lacks flicker"; fail=1; }
  flips=$(grep -c '"against": "converged"' "$T/out/report.json")
  [ "$flips" -eq 8 ] || { echo "FAIL: report.json has FLIP for $flips runs, want 8"; fail=1; }
  grep -q '<th>FLIP (mean)</th>' "$T/out/index.html" || { echo "FAIL: the table has no FLIP column"; fail=1; }
  grep -q ' FLIP ' "$T/out/table.txt" || { echo "FAIL: table.txt has no FLIP column"; fail=1; }
  head -1 "$T/out/report.csv" | grep -q ',flip,' || { echo "FAIL: report.csv has no flip column"; fail=1; }
  for a in 'data-technique="mvr"' 'data-family="multi-view maps"' 'data-family="single map"' '<text class="label'; do
    grep -q "$a" "$T/out/plot.svg" || { echo "FAIL: plot.svg lacks $a"; fail=1; }
  done
  imgs=$(grep -o '<img src=' "$T/out/index.html" | wc -l)

  # --virtual-time-budget lets the load handler run before the DOM is dumped.
  HOME="$T" timeout 120 "$CHROMIUM" --headless=new --no-sandbox --disable-gpu --no-first-run --disable-extensions \
    --user-data-dir="$T/profile" --enable-logging=stderr --v=0 --virtual-time-budget=10000 \
    --dump-dom "file://$T/out/index.html" >"$T/dom.html" 2>"$T/chromium.err"
  rc=$?
  [ "$rc" -eq 0 ] || { echo "FAIL: chromium exit $rc"; tail -20 "$T/chromium.err"; exit 1; }
  loaded=$(sed -n 's/.*data-images="\([0-9]*\/[0-9]*\)".*/\1/p' "$T/dom.html" | head -1)
  points=$(sed -n 's/.*data-plot-points="\([0-9]*\)".*/\1/p' "$T/dom.html" | head -1)
  unlabelled=$(sed -n 's/.*data-unlabelled-points="\([0-9]*\)".*/\1/p' "$T/dom.html" | head -1)
  clashes=$(sed -n 's/.*data-family-colour-clashes="\([0-9]*\)".*/\1/p' "$T/dom.html" | head -1)
  echo "chromium: images loaded $loaded (page has $imgs), plot points $points, unlabelled $unlabelled, colour clashes $clashes"
  [ "$unlabelled" = 0 ] || { echo "FAIL: $unlabelled plot points without their label"; fail=1; }
  [ "$clashes" = 0 ] || { echo "FAIL: $clashes colours shared by two families"; fail=1; }
  [ "$loaded" = "$imgs/$imgs" ] && [ "$imgs" -gt 0 ] || { echo "FAIL: not every image loaded: $loaded"; fail=1; }
  [ "$points" = 8 ] || { echo "FAIL: plot shows $points points, want 8"; fail=1; }
  if grep -q ':CONSOLE' "$T/chromium.err"; then
    echo "FAIL: console messages:"; grep ':CONSOLE' "$T/chromium.err"; fail=1
  fi
  # A broken page must be caught: the check is not vacuous.
  rm "$T/out/pcss__samples-4.png"
  HOME="$T" timeout 120 "$CHROMIUM" --headless=new --no-sandbox --disable-gpu --no-first-run --disable-extensions \
    --user-data-dir="$T/profile" --virtual-time-budget=10000 --dump-dom "file://$T/out/index.html" >"$T/dom2.html" 2>/dev/null
  broken=$(sed -n 's/.*data-images="\([0-9]*\/[0-9]*\)".*/\1/p' "$T/dom2.html" | head -1)
  [ "$broken" = "$((imgs - 1))/$imgs" ] || { echo "FAIL: a missing image was not detected ($broken)"; fail=1; }
}

defaultScene() {
  # The default scene with every technique (the first report a user opens, smaller): the labels
  # shown by default do not overlap, each point is labelled, the families keep their colours.
  # (raytrace-converged is one of `all`: capped at its minimum, the 2048 samples a pixel of its
  # visibility, or its adaptive shading would take most of the run.)
  "$P" compare --techniques all --samples 8 -W 96 -H 96 --timing-frames 1 --warmup 0 \
    --param reference-max-samples=2048 -o "$T/default" 2>"$T/err2"
  rc=$?
  if [ "$rc" -eq 77 ] || grep -q "no GL context\|cannot create.*context" "$T/err2"; then cat "$T/err2"; exit 77; fi
  [ "$rc" -eq 0 ] || { echo "FAIL: compare of the default scene"; tail -5 "$T/err2"; fail=1; }
  HOME="$T" timeout 120 "$CHROMIUM" --headless=new --no-sandbox --disable-gpu --no-first-run --disable-extensions \
    --user-data-dir="$T/profile" --enable-logging=stderr --v=0 --virtual-time-budget=10000 \
    --dump-dom "file://$T/default/index.html" >"$T/dom3.html" 2>"$T/chromium3.err"
  attr() { sed -n "s/.*data-$1=\"\([0-9]*\)\".*/\1/p" "$T/dom3.html" | head -1; }
  echo "default scene: points $(attr plot-points), labels wanted $(attr labels-wanted) shown $(attr labels-shown)" \
    "(wanted but hidden $(attr wanted-labels-hidden)), overlapping $(attr label-overlaps)," \
    "unlabelled $(attr unlabelled-points), colour clashes $(attr family-colour-clashes)"
  [ "$(attr plot-points)" -ge 20 ] || { echo "FAIL: the default scene's plot has $(attr plot-points) points"; fail=1; }
  # The labels shown depend on where the timings put the points; what must hold is that every
  # label the plot wants (the Pareto front's, each family's best: at least one per family, five
  # families here) is shown, beside its point or on a leader line.
  [ "$(attr labels-wanted)" -ge 5 ] || { echo "FAIL: only $(attr labels-wanted) labels wanted"; fail=1; }
  [ "$(attr wanted-labels-hidden)" = 0 ] || { echo "FAIL: $(attr wanted-labels-hidden) wanted labels hidden"; fail=1; }
  [ "$(attr labels-shown)" -ge "$(attr labels-wanted)" ] || { echo "FAIL: only $(attr labels-shown) labels shown"; fail=1; }
  [ "$(attr label-overlaps)" = 0 ] || { echo "FAIL: $(attr label-overlaps) pairs of shown labels overlap"; fail=1; }
  [ "$(attr unlabelled-points)" = 0 ] || { echo "FAIL: unlabelled points on the default scene"; fail=1; }
  [ "$(attr family-colour-clashes)" = 0 ] || { echo "FAIL: families share colours on the default scene"; fail=1; }
  if grep -q ':CONSOLE' "$T/chromium3.err"; then
    echo "FAIL: console messages:"; grep ':CONSOLE' "$T/chromium3.err"; fail=1
  fi
}

case "$PART" in
  sweep) sweep ;;
  default) defaultScene ;;
  *) echo "FAIL: unknown part '$PART' (sweep, default)"; exit 1 ;;
esac
[ "$fail" -eq 0 ] && echo "ok: report loads in chromium"
exit "$fail"
