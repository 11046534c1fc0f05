#!/bin/sh
# A GPU run prepared: the GL render tests and `penumbra bench --quick` on a
# bare machine with an NVIDIA GPU and no packages, from a build made on this Debian machine.
#
#   sh bench/gpu.sh pack [BUILD_DIR]     here (default build/): the binaries, stripped, and the
#                                        shared libraries they need that are not the system's or
#                                        the driver's (ldd), as .gpu-pack/pack.tar.gz (git-ignored,
#                                        ~24 MB: libembree3 is most of it); the
#                                        glvnd loader packages into .gl/ (apt-get download) when
#                                        they are not there yet.
#   sh bench/gpu.sh run [BENCH ARGS...]  there, in the repository root with .gpu-pack/ and .gl/:
#                                        unpacks the glvnd loaders, points glvnd at NVIDIA's EGL,
#                                        runs the GL render tests, `penumbra bench --quick` and
#                                        the dcs-scale study at full size (plus BENCH ARGS) into
#                                        bench/results/<renderer>/.
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
UNPACKED="${PENUMBRA_PACK_DIR:-/tmp/penumbra-pack}"  # where `run` unpacks it
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
  stage=$(mktemp -d)
  rm -rf "$PACK" && mkdir -p "$PACK" "$stage/bin" "$stage/lib"
  bins="$B/src/cli/penumbra"
  for t in $GL_TESTS; do
    [ -x "$B/tests/$t" ] || die "$B/tests/$t: not built"
    bins="$bins $B/tests/$t"
  done
  for b in $bins; do
    strip --strip-debug -o "$stage/bin/$(basename "$b")" "$b"
    ldd "$b" | awk '/=> \// { print $3 }' | while read -r lib; do
      name=$(basename "$lib")
      system_lib "$name" && continue
      [ -e "$stage/lib/$name" ] || strip --strip-debug -o "$stage/lib/$name" "$(readlink -f "$lib")"
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
  # The models scenes name as "assimp:<path>" (Debian assimp-testmodels, /usr/share/assimp/models).
  mkdir -p "$stage/assimp"
  grep -rhoE 'assimp:[^" ]+\.(glb|gltf|obj|ply|off|stl)' scenes bench | sort -u | sed 's/^assimp://' | while read -r m; do
    [ -e "/usr/share/assimp/models/$m" ] || continue
    mkdir -p "$stage/assimp/$(dirname "$m")" && cp "/usr/share/assimp/models/$m" "$stage/assimp/$m"
  done
  tar -C "$stage" -czf "$PACK/pack.tar.gz" bin lib assimp
  echo "packed $(ls "$stage/bin" | wc -l) binaries, $(ls "$stage/lib" | wc -l) libraries ($(ls "$stage/lib" | tr '\n' ' ')), $(du -sh "$PACK/pack.tar.gz" | cut -f1) -> $PACK/pack.tar.gz (source dir $src)"
  rm -rf "$stage"
}

run() {
  [ -f "$PACK/pack.tar.gz" ] || die "no $PACK/pack.tar.gz (run 'sh bench/gpu.sh pack' on the build machine, carry $PACK and $GL_DEBS)"
  rm -rf "$UNPACKED" && mkdir -p "$UNPACKED" && tar -C "$UNPACKED" -xzf "$PACK/pack.tar.gz"
  if ls "$GL_DEBS"/*.deb >/dev/null 2>&1 && ! ldconfig -p 2>/dev/null | grep -q 'libEGL.so.1 '; then
    for f in "$GL_DEBS"/*.deb; do dpkg -x "$f" /; done
    ldconfig
  fi
  for f in /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json /usr/share/glvnd/egl_vendor.d/10_nvidia.json; do
    if [ -e "$f" ] && [ -z "${__EGL_VENDOR_LIBRARY_FILENAMES:-}" ]; then export __EGL_VENDOR_LIBRARY_FILENAMES="$f"; fi
  done
  export LD_LIBRARY_PATH="$UNPACKED/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  if [ ! -d /usr/share/assimp/models ] && [ -n "$(ls "$UNPACKED/assimp" 2>/dev/null)" ]; then
    mkdir -p /usr/share/assimp/models && cp -r "$UNPACKED/assimp/." /usr/share/assimp/models/
  fi
  src=$(cat "$PACK/source-dir")
  if [ ! -e "$src/scenes" ]; then  # the tests' PENUMBRA_SOURCE_DIR: this checkout
    mkdir -p "$(dirname "$src")" && ln -sfn "$PWD" "$src"
  fi
  for b in "$UNPACKED"/bin/*; do
    missing=$(ldd "$b" | grep 'not found' || true)
    [ -z "$missing" ] || die "$(basename "$b"): libraries not found: $missing"
    # Every library that is not the machine's own comes from the pack.
    ldd "$b" | awk '/=> \// { print $3 }' | while read -r lib; do
      system_lib "$(basename "$lib")" || case "$lib" in "$UNPACKED"/lib/*) ;; *) die "$(basename "$b"): $lib is not from the pack" ;; esac
    done
  done
  log=$(mktemp -d)
  "$UNPACKED/bin/penumbra" list >/dev/null
  start=$(date +%s)
  failed=0
  for t in $GL_TESTS; do
    echo "== $t"
    rc=0
    "$UNPACKED/bin/$t" --gtest_brief=1 > "$log/$t.txt" 2>&1 || rc=$?
    tail -3 "$log/$t.txt"
    # 77: no GL context, which on the GPU machine is a failure, not a skip.
    [ "$rc" -eq 0 ] || { echo "$t: exit $rc"; failed=1; }
  done
  echo "== penumbra bench --quick $*"
  rc=0
  "$UNPACKED/bin/penumbra" bench --quick "$@" || rc=$?
  [ "$rc" -eq 0 ] || { echo "bench: exit $rc"; failed=1; }
  # The dcs-at-scale study at its full sizes (dcs raster and compute paths on the engine, 256^2 and
  # 512^2, 16 and 64 samples): the question a GPU answers (few graphics units, compute on all).
  echo "== penumbra bench --studies dcs-scale $*"
  rc=0
  "$UNPACKED/bin/penumbra" bench --studies dcs-scale "$@" || rc=$?
  [ "$rc" -eq 0 ] || { echo "bench dcs-scale: exit $rc"; failed=1; }
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
    # The GL tests and the bench study shortened (GTEST_FILTER, one study): the path, not the numbers.
    out=/tmp/penumbra-gpu-local
    export GTEST_FILTER="${GTEST_FILTER:-Timing*:*Pipeline*}"
    rm -rf "$out" && run -o "$out" --studies techniques ;;
  *) sed -n '2,20p' "$0" | sed 's/^# \{0,1\}//'; exit 2 ;;
esac
