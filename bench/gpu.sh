#!/bin/sh
# A GPU run prepared (issue 15 section 5): the GL render tests and `penumbra bench --quick` on a
# bare machine with an NVIDIA GPU and no packages, from a build made on this Debian machine.
#
#   sh bench/gpu.sh pack [BUILD_DIR]     here (default build/): the binaries, stripped, and the
#                                        shared libraries they need that are not the system's or
#                                        the driver's (ldd), into .gpu-pack/ (git-ignored); the
#                                        glvnd loader packages into .gl/ (apt-get download) when
#                                        they are not there yet.
#   sh bench/gpu.sh run [BENCH ARGS...]  there, in the repository root with .gpu-pack/ and .gl/:
#                                        unpacks the glvnd loaders, points glvnd at NVIDIA's EGL,
#                                        runs the GL render tests and `penumbra bench --quick`
#                                        (plus BENCH ARGS) into bench/results/<renderer>/.
#   sh bench/gpu.sh local [BUILD_DIR]    here: pack, then `run` on this machine's GL (llvmpipe)
#                                        with only the pack's libraries added, results under
#                                        /tmp: the path the GPU machine takes.
#
# Left to the GPU machine (never packed): glibc (libc, libm, libdl, libpthread, librt, ld-linux),
# the GL loaders (glvnd: libEGL, libGL, libGLX, libOpenGL, libGLdispatch, libGLES) and the driver
# (libnvidia-*, libcuda). OSMesa is loaded only when asked for (src/gl/context.cpp), so neither it
# nor its LLVM travels. The device tool carries 64 MiB: `carry` .gpu-pack and .gl.
set -eu
PACK=.gpu-pack
GL_DEBS=".gl"
GL_TESTS="test_render test_render_resources test_render_compare"

die() { echo "bench/gpu.sh: $*" >&2; exit 1; }

# Whether a library (by file name) is the GPU machine's to provide.
system_lib() {
  case "$1" in
    linux-vdso*|ld-linux*|libc.so*|libm.so*|libdl.so*|libpthread.so*|librt.so*|libresolv.so*) return 0 ;;
    libEGL*|libGL.so*|libGLX*|libOpenGL*|libGLdispatch*|libGLES*|libnvidia*|libcuda*) return 0 ;;
  esac
  return 1
}

pack() {
  B="${1:-build}"
  [ -x "$B/src/cli/penumbra" ] || die "$B/src/cli/penumbra: no build (cmake --build $B first)"
  src=$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$B/CMakeCache.txt")
  rm -rf "$PACK" && mkdir -p "$PACK/bin" "$PACK/lib"
  bins="$B/src/cli/penumbra"
  for t in $GL_TESTS; do
    [ -x "$B/tests/$t" ] || die "$B/tests/$t: not built"
    bins="$bins $B/tests/$t"
  done
  for b in $bins; do
    strip --strip-debug -o "$PACK/bin/$(basename "$b")" "$b"
    ldd "$b" | awk '/=> \// { print $3 }' | while read -r lib; do
      name=$(basename "$lib")
      system_lib "$name" && continue
      [ -e "$PACK/lib/$name" ] || strip --strip-debug -o "$PACK/lib/$name" "$(readlink -f "$lib")"
    done
  done
  # Where the tests were built: they find scenes/ and tests/data/ under it (PENUMBRA_SOURCE_DIR).
  echo "$src" > "$PACK/source-dir"
  git rev-parse HEAD > "$PACK/commit" 2>/dev/null || echo unknown > "$PACK/commit"
  if ! ls "$GL_DEBS"/*.deb >/dev/null 2>&1; then
    # The glvnd loaders a bare machine lacks (/work/.library/device/README.md), as .deb files.
    mkdir -p "$GL_DEBS" /tmp/amd64/partial
    o='-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64'
    # shellcheck disable=SC2086
    if apt-get $o update >/dev/null && (cd "$GL_DEBS" && apt-get $o download libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2 >/dev/null); then
      echo "glvnd loaders: $(ls "$GL_DEBS" | tr '\n' ' ')"
    else
      echo "bench/gpu.sh: could not download the glvnd loaders into $GL_DEBS; the GPU machine must have libEGL.so.1" >&2
    fi
  fi
  echo "packed $(ls "$PACK/bin" | wc -l) binaries, $(ls "$PACK/lib" | wc -l) libraries, $(du -sh "$PACK" | cut -f1) -> $PACK (source dir $src)"
}

run() {
  [ -d "$PACK/bin" ] || die "no $PACK (run 'sh bench/gpu.sh pack' on the build machine, carry $PACK and $GL_DEBS)"
  if ls "$GL_DEBS"/*.deb >/dev/null 2>&1 && ! ldconfig -p 2>/dev/null | grep -q 'libEGL.so.1 '; then
    for f in "$GL_DEBS"/*.deb; do dpkg -x "$f" /; done
    ldconfig
  fi
  for f in /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json /usr/share/glvnd/egl_vendor.d/10_nvidia.json; do
    if [ -e "$f" ] && [ -z "${__EGL_VENDOR_LIBRARY_FILENAMES:-}" ]; then export __EGL_VENDOR_LIBRARY_FILENAMES="$f"; fi
  done
  export LD_LIBRARY_PATH="$PWD/$PACK/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  src=$(cat "$PACK/source-dir")
  if [ ! -e "$src/scenes" ]; then  # the tests' PENUMBRA_SOURCE_DIR: this checkout
    mkdir -p "$(dirname "$src")" && ln -sfn "$PWD" "$src"
  fi
  missing=$(ldd "$PACK/bin/penumbra" | grep 'not found' || true)
  [ -z "$missing" ] || die "libraries not found: $missing"
  log=$(mktemp -d)
  "$PACK/bin/penumbra" list >/dev/null
  start=$(date +%s)
  failed=0
  for t in $GL_TESTS; do
    echo "== $t"
    rc=0
    "$PACK/bin/$t" --gtest_brief=1 > "$log/$t.txt" 2>&1 || rc=$?
    tail -3 "$log/$t.txt"
    # 77: no GL context, which on the GPU machine is a failure, not a skip.
    [ "$rc" -eq 0 ] || { echo "$t: exit $rc"; failed=1; }
  done
  echo "== penumbra bench --quick $*"
  rc=0
  "$PACK/bin/penumbra" bench --quick "$@" || rc=$?
  [ "$rc" -eq 0 ] || { echo "bench: exit $rc"; failed=1; }
  dir=""
  for a in "$@"; do [ "${prev:-}" = "-o" ] || [ "${prev:-}" = "--output" ] && dir="$a"; prev="$a"; done
  [ -n "$dir" ] || dir=$(dirname "$(ls -t bench/results/*/machine.txt | head -1)")
  mkdir -p "$dir/tests"
  cp "$log"/*.txt "$dir/tests/"
  {
    echo "bench/gpu.sh run: commit $(cat "$PACK/commit"), $(( $(date +%s) - start )) s, exit $failed"
    grep -h "renderer" "$dir/machine.txt" || true
    for t in $GL_TESTS; do echo "$t: $(grep -E '^\[  (PASSED|FAILED)' "$log/$t.txt" | tr '\n' ' ')"; done
  } > "$dir/tests/summary.txt"
  cat "$dir/tests/summary.txt"
  rm -rf "$log"
  return $failed
}

cmd="${1:-}"; [ $# -gt 0 ] && shift
case "$cmd" in
  pack) pack "$@" ;;
  run) run "$@" ;;
  local)
    pack "${1:-build}"
    # This machine's GL (Mesa llvmpipe) through the same loader path, only the pack's libraries added.
    out=/tmp/penumbra-gpu-local
    rm -rf "$out" && run -o "$out" --studies techniques ;;
  *) sed -n '2,20p' "$0" | sed 's/^# \{0,1\}//'; exit 2 ;;
esac
