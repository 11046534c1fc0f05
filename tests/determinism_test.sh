#!/bin/sh
# Hard case 24 (../shared/docs/hard-cases.md): determinism. Cases 1, 13 and 15 rendered with
# LP_NUM_THREADS=1 and 8 (separate processes: llvmpipe reads it when its screen is created),
# twice each, must give bit-identical pixels for the blend (dcs counters), shadow-volume count
# (hard-sv), depth-test (mvr) and integer-atomic (vwss, reproject) paths, for the single-map
# filters (pcss, vssm, msm, msm-soft, evsm) and the denoiser (raytrace-denoised, its filter on
# all cores); the EGL and OSMesa backends must agree bit for bit too. Pixel data is compared with
# exr_diff (colour and visibility layers), not the files' bytes.
# Usage: determinism_test.sh PENUMBRA EXR_DIFF SRCDIR GROUP: a group of scenes and techniques
# (the case below; one CTest test each, tests/determinism.cmake, so that each stays well under
# 30 s).
# Exits 77 (skipped) only without a GL context.
P="$1"; DIFF="$2"; SRC="$3"; GROUP="$4"; T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
SIZE=${DETERMINISM_SIZE:-128}
fail=0; runs=0; compared=0
"$P" render -W 32 -H 32 --samples 1 -o "$T/probe.exr" 2>"$T/err"; rc=$?
if [ "$rc" -eq 77 ]; then echo "no GL context: skipped"; cat "$T/err"; exit 77; fi
if [ "$rc" -ne 0 ]; then echo "FAIL: probe render exited $rc"; cat "$T/err"; exit 1; fi
# The EGL = OSMesa pairings need OSMesa, which has only Mesa's software rasterisers: under
# GALLIUM_DRIVER=zink (tests/zink.sh) it exits 77 with a reason and those pairings are skipped.
HAVE_OSMESA=1
"$P" render --backend osmesa -W 32 -H 32 --samples 1 -o "$T/probe_osmesa.exr" 2>"$T/err"; rc=$?
if [ "$rc" -eq 77 ]; then HAVE_OSMESA=0; echo "skipped: EGL = OSMesa pairings: $(cat "$T/err" | tail -n 1)"
elif [ "$rc" -ne 0 ]; then echo "FAIL: OSMesa probe render exited $rc"; cat "$T/err"; exit 1; fi

render() {  # render OUT BACKEND THREADS SCENE TECH [params...]
  out="$1"; backend="$2"; threads="$3"; scene="$4"; tech="$5"; shift 5
  if ! LP_NUM_THREADS="$threads" "$P" render "$SRC/$scene" -t "$tech" -W "$SIZE" -H "$SIZE" --samples "$SAMPLES" \
        --backend "$backend" "$@" -o "$out" 2>"$T/err"; then
    echo "FAIL: render $tech $scene ($backend, LP_NUM_THREADS=$threads)"; cat "$T/err"; fail=1; return 1
  fi
  runs=$((runs + 1))
}
same() {  # same A B WHAT
  compared=$((compared + 1))
  if ! "$DIFF" "$1" "$2" >"$T/diff" 2>&1; then
    echo "FAIL: $3 differ:"; cat "$T/diff"; fail=1; return 1
  fi
}
# check SCENE TECH [params...]: EGL with LP_NUM_THREADS 1 and 8, twice each; with OSMESA=1 also
# the OSMesa backend (8 threads) against EGL.
check() {
  scene="$1"; tech="$2"; shift 2
  base="$T/$(basename "$scene" .json)_$tech"
  for threads in 1 8; do
    for run in 1 2; do render "${base}_t${threads}_r$run.exr" egl "$threads" "$scene" "$tech" "$@" || return; done
  done
  ok=1; what="LP_NUM_THREADS 1/8 x2"
  same "${base}_t1_r1.exr" "${base}_t1_r2.exr" "$tech $scene: LP_NUM_THREADS=1 run 1 and 2" || ok=0
  same "${base}_t8_r1.exr" "${base}_t8_r2.exr" "$tech $scene: LP_NUM_THREADS=8 run 1 and 2" || ok=0
  same "${base}_t1_r1.exr" "${base}_t8_r1.exr" "$tech $scene: LP_NUM_THREADS=1 and 8" || ok=0
  if [ "${OSMESA:-0}" -eq 1 ] && [ "$HAVE_OSMESA" -eq 1 ]; then
    render "${base}_osmesa.exr" osmesa 8 "$scene" "$tech" "$@" || return
    same "${base}_t8_r1.exr" "${base}_osmesa.exr" "$tech $scene: EGL and OSMesa" || ok=0
    what="$what, EGL = OSMesa"
  fi
  [ $ok -eq 1 ] && echo "ok: $tech $scene ($SAMPLES samples): bit-identical ($what)"
}
SAMPLES=16; MAP="--param map=256"
CUBE=scenes/hard/01-cube-on-plane.json
case "$GROUP" in
cube-volumes)
  # Case 1: the shadow-volume count and the blended dcs counters, both backends.
  for t in hard-sv dcs; do OSMESA=1 check $CUBE $t; done ;;
cube-maps)
  # Case 1: the depth-test (mvr) and integer-atomic (vwss, reproject) paths, both backends.
  for t in mvr vwss reproject; do OSMESA=1 check $CUBE $t $MAP; done
  # Measured, not asserted: reproject-unsync writes its maps with plain stores (last writer
  # wins), a race by design; one llvmpipe thread is deterministic, several are not (docs/testing.md
  # "Determinism").
  base="$T/unsync"
  render "${base}_t1_r1.exr" egl 1 $CUBE reproject-unsync $MAP &&
    render "${base}_t1_r2.exr" egl 1 $CUBE reproject-unsync $MAP &&
    same "${base}_t1_r1.exr" "${base}_t1_r2.exr" "reproject-unsync, LP_NUM_THREADS=1 run 1 and 2" &&
    echo "ok: reproject-unsync with LP_NUM_THREADS=1: bit-identical"
  for run in 1 2 3; do
    render "${base}_t8_r$run.exr" egl 8 $CUBE reproject-unsync $MAP || break
    echo "measured: reproject-unsync LP_NUM_THREADS=8 run $run against LP_NUM_THREADS=1:" \
         "$("$DIFF" "${base}_t1_r1.exr" "${base}_t8_r$run.exr" | grep visibility || echo identical)"
  done ;;
cube-filters)
  # Case 1: the single-map filters' summed-area tables, both backends.
  for t in pcss vssm msm; do OSMESA=1 check $CUBE $t $MAP; done ;;
cube-moments)
  # Case 1: the moment filters, both backends, and the denoiser (its filter on all cores).
  for t in msm-soft evsm; do OSMESA=1 check $CUBE $t $MAP; done
  check $CUBE raytrace-denoised ;;
plates-volumes)
  # Case 13: stacks of thin plates (17: past dcs's narrowest counter base; 257: past 8 bits).
  for t in hard-sv dcs; do check tests/data/scene/13-plates-17.json $t; OSMESA=1 check tests/data/scene/13-plates-257.json $t; done ;;
plates-maps)
  for t in mvr vwss; do check tests/data/scene/13-plates-17.json $t $MAP; done ;;
two-plates)
  # Case 15: overlapping penumbrae of two plates.
  for t in hard-sv dcs; do check scenes/hard/15-two-plates.json $t; done
  for t in mvr vwss; do check scenes/hard/15-two-plates.json $t $MAP; done ;;
sphere-grid-dcs)
  # Case 15: the 9x9x9 sphere grid (46k triangles), 8 samples; dcs alone (3 s a render with
  # one llvmpipe thread).
  SAMPLES=8 check scenes/hard/15-sphere-grid.json dcs ;;
sphere-grid)
  SAMPLES=8 check scenes/hard/15-sphere-grid.json hard-sv
  for t in mvr vwss; do SAMPLES=8 check scenes/hard/15-sphere-grid.json $t $MAP; done ;;
*) echo "FAIL: unknown group '$GROUP' (see tests/determinism.cmake)"; exit 1 ;;
esac
[ "$runs" -gt 0 ] || { echo "FAIL: group $GROUP rendered nothing"; exit 1; }
echo "$runs renders, $compared comparisons"
exit $fail
