#!/bin/sh
# CLI exit codes and one-line errors (docs/cli.md "Exit codes"). Usage: cli_test.sh PENUMBRA SRCDIR PART
# with PART inputs (usage errors and bad inputs, all refused before any GL work, and the LUT
# tool: no GL context needed) or render (rendering, compare, GL limits: exits 77, skipped,
# without a GL context). One CTest test each (tests/render.cmake).
P="$1"; SRC="$2"; PART="$3"; T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
fail=0
expect() {  # expect CODE PATTERN -- command...
  code="$1"; pattern="$2"; shift 3
  "$@" >"$T/out" 2>"$T/err"; got=$?
  if [ "$got" -ne "$code" ]; then echo "FAIL: exit $got, want $code: $*"; cat "$T/err"; fail=1; return; fi
  if [ -n "$pattern" ] && ! grep -q -- "$pattern" "$T/err"; then
    echo "FAIL: stderr lacks '$pattern': $*"; cat "$T/err"; fail=1; return
  fi
  if [ "$code" -ne 0 ] && [ "$(grep -c '^penumbra: ' "$T/err")" -ne 1 ]; then
    echo "FAIL: want exactly one 'penumbra: ' error line: $*"; cat "$T/err"; fail=1; return
  fi
  echo "ok: exit $got: $*"
}
inputs() {
  expect 0 "" -- "$P" list
  "$P" list | grep -q '^hard-sv ' || { echo "FAIL: list lacks hard-sv"; fail=1; }
  expect 2 "" -- "$P" frobnicate
  expect 2 "unknown technique" -- "$P" render --technique nope -o "$T/x.png"
  expect 1 "missing.json" -- "$P" info "$T/missing.json"
  printf '{ "lights": [ ' > "$T/broken.json"
  expect 1 "broken.json" -- "$P" info "$T/broken.json"
  expect 2 "\-\-samples" -- "$P" render --samples 0 -o "$T/x.png"
  expect 2 "\-\-samples" -- "$P" render --samples 100000 -o "$T/x.png"
  expect 2 ".exr or .png" -- "$P" render -o "$T/x.txt"
  expect 1 "does not exist" -- "$P" render -o "$T/no/such/dir/x.png"
  expect 1 "/etc/hostname" -- "$P" render -o /etc/hostname/x.png
  expect 2 "\-\-backend" -- "$P" render --backend vulkan -o "$T/x.png"
  expect 2 "\-\-shape" -- "$P" lut --shape triangle -o "$T"
  expect 2 "\-\-line" -- "$P" lut --line 3 -o "$T"
  # Each subcommand takes only the options it uses.
  expect 2 "not expected: \-\-shading" -- "$P" lut --shading ratio -o "$T"
  expect 2 "not expected: \-\-param" -- "$P" lut --param map=64 -o "$T"
  expect 2 "not expected: \-\-samples" -- "$P" info --samples 4
  expect 0 "" -- "$P" lut --samples 8 --line 16 --cube 4 -o "$T"
  # Studies (docs/studies.md): a folder without a plan, a bad shard or index, a corrupt plan row;
  # all refused before any job runs (tests/study_run_test.sh runs them).
  expect 2 "penumbra study plan" -- "$P" study run "$T"
  expect 2 "penumbra study plan" -- "$P" study merge "$T"
  expect 0 "" -- "$P" study plan "$SRC/tests/studies/tiny.json" -o "$T/study"
  for shard in 2/2 1/0 -1/2 x 1/2/3 "1 /2"; do
    expect 2 "\-\-shard" -- "$P" study run "$T/study" --shard "$shard"
  done
  expect 2 "\-\-index" -- "$P" study run "$T/study" --index 34
  expect 2 "not both" -- "$P" study run "$T/study" --index 1 --shard 0/2
  expect 2 "\-j" -- "$P" study run "$T/study" -j 0
  sed '3s/"kind":"[a-z]*"/"kind":"guess"/' "$T/study/jobs.jsonl" > "$T/jobs" && mv "$T/jobs" "$T/study/jobs.jsonl"
  expect 2 "jobs.jsonl:3: a job of unknown kind 'guess'" -- "$P" study run "$T/study"
  printf '{"id": 1}\n' > "$T/study/jobs.jsonl"
  expect 2 "jobs.jsonl:1: not a job row" -- "$P" study merge "$T/study"
  test -s "$T/edge_rect_stratified_correlated_n8_seed1.lut" || { echo "FAIL: lut wrote no table"; fail=1; }
  # Lut creates a missing output folder as compare does (it refused it),
  # and a device or a file given as a folder says so (it said "does not exist").
  expect 0 "" -- "$P" lut --samples 4 --line 16 --cube 4 -o "$T/new/lut/dir"
  test -s "$T/new/lut/dir/edge_rect_stratified_correlated_n4_seed1.lut" || { echo "FAIL: lut did not create its folder"; fail=1; }
  expect 1 "'/dev/null' is a device, socket or pipe, not a folder" -- "$P" lut -o /dev/null
  expect 1 "'/dev/null' is a device, socket or pipe, not a folder" -- "$P" compare -W 16 -H 16 -o /dev/null
  expect 1 "'/dev/null' is a device, socket or pipe, not a folder" -- "$P" render -o /dev/null/x.png
  printf x > "$T/afile"
  expect 1 "cannot create folder '$T/afile/sub'" -- "$P" lut -o "$T/afile/sub"
  # --param naming no technique's key lists what the run's techniques know, never the key itself.
  expect 2 "parameter 'bogus' (they take no parameters)" -- "$P" render -t none -W 16 -H 16 --param bogus=1 -o "$T/p.png"
  expect 2 "parameter 'bogus' (known: pcf, map," -- "$P" render -t mvr -W 16 -H 16 --param bogus=1 -o "$T/p.png"
  # strtod read hex ("0x100") and hex floats as numbers.
  expect 2 "map: expected a number, got '0x100'" -- "$P" render -t mvr -W 16 -H 16 --param map=0x100 -o "$T/p.png"
  if grep -q "known:.*bogus" "$T/err"; then echo "FAIL: --param lists the unknown key as known"; fail=1; fi
  # --log is accepted after the subcommand too; an unknown level is refused (spdlog read it as off).
  expect 2 "\-\-log: bogus not in" -- "$P" info --log bogus
  expect 0 "" -- "$P" info --log off
  # A folder given as a mesh: "is a folder", not "not found".
  mkdir "$T/folder.obj"
  expect 1 "folder.obj: is a folder, not a file" -- "$P" info "$T/folder.obj"
  # Bad inputs (hard-cases.md, "Bad inputs: expected behaviour"), all refused before any GL work.
  expect 2 "\-W/\-H" -- "$P" render -W 0 -H 0 -o "$T/x.png"
  # -1 was read as "the scene's size"; duplicate techniques were merged; 'all' with others was "unknown".
  expect 2 "\-W/\-H: image size must be positive, got -1 x the scene's" -- "$P" render -W -1 -o "$T/x.png"
  expect 2 "\-\-techniques: 'dcs' given twice" -- "$P" compare --techniques dcs,hard-sv,dcs -o "$T/twice"
  expect 2 "\-\-techniques: 'all' is every technique and stands alone" -- "$P" compare --techniques all,dcs -o "$T/twice"
  test ! -e "$T/twice" || { echo "FAIL: a refused compare made its folder"; fail=1; }
  expect 2 "\-\-samples" -- "$P" render --samples 129 -o "$T/x.png"
  expect 1 "size: an area light needs a positive size" -- "$P" render --set lights.0.size=0 -o "$T/x.png"
  test ! -e "$T/x.png" || { echo "FAIL: an image was written for a bad input"; fail=1; }
  # Read-only output folder. Root ignores mode bits, so as root the case runs as nobody.
  mkdir "$T/ro" && chmod 555 "$T/ro" && chmod 755 "$T"
  as_user=""; [ "$(id -u)" -eq 0 ] && as_user="setpriv --reuid=65534 --regid=65534 --clear-groups --"
  expect 1 "is not writable" -- $as_user "$P" render -o "$T/ro/x.png"
  # A mesh with dropped faces loads and `info` counts every drop; a glTF reaching outside its
  # folder is refused naming the file and the buffer.
  printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 0 1\nf 1 2 3\nf 1 2 10\nf 1 1 2\nf 1 2 4\nf 2 3 1\n' > "$T/bad.obj"
  expect 0 "" -- "$P" info "$T/bad.obj"
  grep -q "1 triangle, 4 dropped (1 invalid index, 1 degenerate, 1 non-finite, 1 duplicate)" "$T/out" ||
    { echo "FAIL: info does not count the dropped faces"; cat "$T/out"; fail=1; }
  printf '{"asset":{"version":"2.0"},"buffers":[{"byteLength":8,"uri":"../x.bin"}]}' > "$T/bad.gltf"
  expect 1 "bad.gltf: buffer 0: uri '../x.bin' leaves its folder" -- "$P" info "$T/bad.gltf"
  # Memory before allocating: a 4096 x 4096 sphere (33.5 M triangles, 5.4 GiB
  # measured) under a 3 GiB address-space limit is refused before it is built, in well under a
  # second (it grew to 17 GB and crashed before). scenes/hard/31-big-sphere.json is its 22.6 M
  # triangle sibling that renders with 4.1 GiB.
  # AddressSanitizer reserves terabytes of shadow address space at start, which ulimit -v forbids:
  # the sanitizer build (tests/sanitize.sh sets ASAN_OPTIONS) runs this case without the limit's
  # refusal, which the normal build checks.
  if [ -n "${ASAN_OPTIONS:-}" ]; then
    echo "skip under AddressSanitizer: the ulimit -v refusal (ASan cannot start under ulimit -v)"
  else
    expect 1 "sphere of 4096 x 4096 segments (33.5 M triangles) needs about" -- \
      sh -c 'ulimit -v 3000000 && exec "$1" render "$2" -t none -W 32 -H 32 --set objects.1.rings=4096 -o "$3"' \
      sh "$P" "$SRC/scenes/hard/31-big-sphere.json" "$T/big.png"
    grep -q "ulimit -v limit" "$T/err" || { echo "FAIL: the refusal does not name the limit"; cat "$T/err"; fail=1; }
  fi
}

render() {
  # Rendering cases need a GL context.
  "$P" render -W 32 -H 32 --samples 1 -o "$T/probe.png" 2>"$T/err"; rc=$?
  if [ "$rc" -eq 77 ]; then echo "no GL context: skipping rendering cases"; exit 77; fi
  expect 0 "" -- "$P" render -W 64 -H 64 --samples 4 -o "$T/a.exr"
  expect 0 "" -- "$P" render -W 16 -H 16 --samples 1 -o "$T/quiet.png" --log warn
  if [ -s "$T/err" ]; then echo "FAIL: render --log warn (after the subcommand) still logged"; cat "$T/err"; fail=1; fi
  test -s "$T/a.exr" || { echo "FAIL: no EXR written"; fail=1; }
  expect 2 "\-W" -- "$P" render -W 0 -H 64 -o "$T/b.png"
  expect 0 "" -- "$P" compare -W 64 -H 64 --samples 4 --techniques hard-sv,none -o "$T/cmp"
  for f in report.json raytrace.exr hard-sv.png hard-sv_heat.png none.exr; do
    test -s "$T/cmp/$f" || { echo "FAIL: compare did not write $f"; fail=1; }
  done
  grep -q '"misclassifiedPixelsOutsideBand"' "$T/cmp/report.json" || { echo "FAIL: report lacks errors"; fail=1; }
  # hard-sv cannot match a 16-sample area light: --max-error must trip (exit 3).
  expect 3 "exceeds --max-error" -- "$P" compare -W 64 -H 64 --samples 16 --techniques hard-sv --max-error 0.0001 -o "$T/cmp2"
  # OSMesa has only Mesa's software rasterisers: under GALLIUM_DRIVER=zink (tests/zink.sh) it is
  # refused with exit 77 and a one-line reason, never a crash; otherwise it renders.
  case "${GALLIUM_DRIVER:-llvmpipe}" in
    llvmpipe|softpipe) expect 0 "" -- "$P" render --backend osmesa -W 32 -H 32 --samples 1 -o "$T/o.png" ;;
    *) expect 77 "GALLIUM_DRIVER=$GALLIUM_DRIVER is not one of OSMesa's drivers" -- \
         "$P" render --backend osmesa -W 32 -H 32 --samples 1 -o "$T/o.png"
       echo "skipped: OSMesa rendering (GALLIUM_DRIVER=$GALLIUM_DRIVER)" ;;
  esac
  # Technique parameters: read by the techniques that know them, refused when none does.
  expect 0 "" -- "$P" compare -W 32 -H 32 --samples 4 --techniques mvr,vwss --param map=64 --param k=1 -o "$T/cmp3"
  expect 2 "no technique of this run has a parameter 'k'" -- "$P" render -t mvr -W 32 -H 32 --param k=1 -o "$T/p.png"
  expect 2 "map: 7 is outside" -- "$P" render -t mvr -W 32 -H 32 --param map=7 -o "$T/p.png"
  expect 2 "pcf: expected one of 1, 5, 9" -- "$P" render -t mvr -W 32 -H 32 --param pcf=4 -o "$T/p.png"
  expect 2 "expected key=value" -- "$P" render -t mvr -W 32 -H 32 --param map -o "$T/p.png"
  expect 2 "given twice" -- "$P" render -t mvr -W 32 -H 32 --param map=64 --param map=128 -o "$T/p.png"
  expect 2 "expected a number" -- "$P" render -t vwss -W 32 -H 32 --param scale=big -o "$T/p.png"
  # Non-finite numbers: refused in one line, before any rendering.
  expect 2 "\-\-time: expected a decimal number, got .nan." -- "$P" render -W 32 -H 32 --time nan -o "$T/n.png"
  expect 2 "\-\-time: must be a finite number of seconds, got inf" -- "$P" compare -W 32 -H 32 --time 1e400 --techniques none -o "$T/cmpn"
  expect 2 "\-\-max-error: must be a finite RMSE >= 0, got -1" -- "$P" compare -W 32 -H 32 --techniques none --max-error -1 -o "$T/cmpn"
  expect 2 "\-\-max-error: expected a decimal number, got .nan." -- "$P" compare -W 32 -H 32 --techniques none --max-error nan -o "$T/cmpn"
  expect 2 "\-\-ppd: must be in .* pixels per degree, got 0" -- "$P" compare -W 32 -H 32 --techniques none --ppd 0 -o "$T/cmpn"
  expect 2 "\-\-ppd: must be in .* pixels per degree, got inf" -- "$P" compare -W 32 -H 32 --techniques none --ppd 1e999 -o "$T/cmpn"
  # CLI11 reads 0x10 as 16 and 010 as 8: numbers are decimal only, every option.
  expect 2 "\-\-samples: expected a decimal number, got .0x10." -- "$P" render -W 32 -H 32 --samples 0x10 -o "$T/n.png"
  expect 2 "\-\-seed: expected a decimal number, got .010." -- "$P" render -W 32 -H 32 --seed 010 -o "$T/n.png"
  expect 2 "\-\-time: expected a decimal number, got .0x1p2." -- "$P" render -W 32 -H 32 --time 0x1p2 -o "$T/n.png"
  expect 2 "\-\-memory-budget: expected a positive size with a unit" -- "$P" --memory-budget 12 info
  test ! -e "$T/n.png" || { echo "FAIL: an image was written for --time nan"; fail=1; }
  # One technique's failure (vssm refuses a map that is not a power of two when it renders) is its
  # row in every output; the others go on; the run ends with exit 1 naming it.
  expect 1 "compare: 1 of 2 technique runs failed (see the report): vssm (vssm: map size 1000 is not a power of two" -- \
    "$P" compare -W 32 -H 32 --samples 4 --techniques vssm,hard-sv --param map=1000 --timing-frames 1 --warmup 0 -o "$T/cmpf"
  grep -q "^vssm  *FAILED: vssm: map size 1000" "$T/cmpf/table.txt" || { echo "FAIL: table.txt lacks the failed row"; fail=1; }
  grep -q "^hard-sv  *[0-9]" "$T/cmpf/table.txt" || { echo "FAIL: table.txt lacks hard-sv's row"; fail=1; }
  grep -q '"status": "failed"' "$T/cmpf/report.json" || { echo "FAIL: report.json lacks the failed run"; fail=1; }
  grep -q ',vssm,.*,failed,vssm: map size 1000' "$T/cmpf/report.csv" || { echo "FAIL: report.csv lacks the failed row"; fail=1; }
  grep -q '<tr class="failed"><td class="l">vssm</td>' "$T/cmpf/index.html" || { echo "FAIL: index.html lacks the failed row"; fail=1; }
  test -s "$T/cmpf/hard-sv.png" || { echo "FAIL: hard-sv did not go on after vssm failed"; fail=1; }
  # Hard case 30: nearly transparent occluders (opacity 3e-9 overflowed dcs's units to -2^31:
  # RMSE 0.98, exit 0); now dcs equals the reference.
  expect 0 "" -- "$P" compare "$SRC/scenes/hard/30-tiny-opacity.json" -W 64 -H 64 --samples 8 --techniques dcs --timing-frames 1 --warmup 0 --max-error 0.001 -o "$T/cmp30"
  # A scene never chooses where files go: its name, from the file or --set, is one harmless
  # component of compare's default folder out/<name> (a name "../../x" wrote outside out/).
  mkdir -p "$T/cwd/a" && sed 's|"name": "01-cube-on-plane"|"name": "../../escape"|' "$SRC/scenes/hard/01-cube-on-plane.json" > "$T/cwd/a/named.json"
  (cd "$T/cwd/a" && "$P" compare named.json -W 16 -H 16 --samples 1 --techniques none --timing-frames 1 --warmup 0 \
      >/dev/null 2>"$T/err") || { echo "FAIL: compare of a scene named ../../escape"; cat "$T/err"; fail=1; }
  test -s "$T/cwd/a/out/_._.._escape/report.json" || { echo "FAIL: no report in out/_._.._escape"; ls -R "$T/cwd"; fail=1; }
  test ! -e "$T/escape" && test ! -e "$T/cwd/escape" || { echo "FAIL: a scene name wrote outside out/"; fail=1; }
  (cd "$T/cwd/a" && "$P" compare named.json --set name=/tmp/abs -W 16 -H 16 --samples 1 --techniques none \
      --timing-frames 1 --warmup 0 >/dev/null 2>"$T/err") || { echo "FAIL: compare --set name=/tmp/abs"; fail=1; }
  test -s "$T/cwd/a/out/_tmp_abs/report.json" || { echo "FAIL: no report in out/_tmp_abs"; fail=1; }
  # One run at a time in a folder (two runs into one folder mixed their images into one report):
  # a second is refused while the first holds the folder.
  mkdir -p "$T/held"
  flock "$T/held/.penumbra-lock" sleep 4 & holder=$!
  sleep 1
  expect 1 "another penumbra run is writing into this folder" -- "$P" compare -W 16 -H 16 --techniques none -o "$T/held"
  wait "$holder"
  # The previous run's report never presents itself beside this run's images: removed at the
  # start, rewritten after every row (marked incomplete until the last).
  printf 'old report' > "$T/cmp/table.txt"
  expect 0 "" -- "$P" compare -W 16 -H 16 --samples 1 --techniques none --timing-frames 1 --warmup 0 -o "$T/cmp"
  if grep -q "old report\|INCOMPLETE" "$T/cmp/table.txt"; then echo "FAIL: a stale or incomplete table after the run"; fail=1; fi
  # A LUT named for plain dcs (exact coverage, reads none) was accepted and ignored; a missing
  # lut-dir fell back to a LUT built in memory.
  expect 2 "lut-file: this dcs counts with the exact coverage test and reads no edge LUT" -- \
    "$P" render -t dcs -W 16 -H 16 --param lut-file="$SRC/luts/edge_rect_stratified_correlated_n16_seed1.lut" -o "$T/l.png"
  expect 2 "lut-file: '/nonexistent.lut': no such file" -- "$P" render -t dcs-lut -W 16 -H 16 --param lut-file=/nonexistent.lut -o "$T/l.png"
  expect 2 "lut-dir: '$T/nolut' is not a folder" -- "$P" render -t dcs-lut -W 16 -H 16 --param lut-dir="$T/nolut" -o "$T/l.png"
  # Refused before the work, naming what: an edge LUT too large for the run's memory (it took
  # 117 s to build before failing), a swept value (as --sweep, before any GL setup), an empty
  # shader folder (it was read as /).
  expect 1 "dcs: an edge LUT of 1 sets with lut-cube 1024 and lut-line 4096 needs about" -- \
    "$P" --memory-budget 256MiB render -t dcs-lut -W 16 -H 16 --seed 7 --param lut-cube=1024 --param lut-line=4096 -o "$T/l.png"
  expect 2 "^penumbra: \-\-sweep: map: expected a number, got 'abc'" -- \
    "$P" compare -W 16 -H 16 --techniques mvr --sweep map=64,abc -o "$T/sw"
  grep -q "renderer:" "$T/err" && { echo "FAIL: a bad --sweep value was found after the GL setup"; fail=1; }
  test ! -e "$T/sw" || { echo "FAIL: a refused compare made its output folder"; fail=1; }
  expect 1 "PENUMBRA_SHADER_DIR: is set but empty" -- env PENUMBRA_SHADER_DIR= "$P" render -W 16 -H 16 -o "$T/l.png"
  # GL limits and out-of-memory: one-line errors, never a crash or a GL error.
  noglerr() { if grep -q 'GL error\|GL: ' "$T/err"; then echo "FAIL: GL error logged"; cat "$T/err"; fail=1; fi; }
  expect 2 "map: 100000 is outside" -- "$P" render -t mvr -W 32 -H 32 --param map=100000 -o "$T/p.png"; noglerr
  expect 2 "image size 100000x32" -- "$P" render -W 100000 -H 32 -o "$T/p.png"; noglerr
  expect 1 "out of GPU memory for 64 depth maps of 16384" -- "$P" render -t mvr -W 32 -H 32 --samples 64 --param map=16384 -o "$T/p.png"; noglerr
  expect 1 "out of memory allocating a 16384 x 16384 RGBA32F texture" -- "$P" render -W 16384 -H 16384 -o "$T/p.png"; noglerr
}

case "$PART" in
  inputs) inputs ;;
  render) render ;;
  *) echo "FAIL: unknown part '$PART' (inputs, render)"; exit 1 ;;
esac
exit $fail
