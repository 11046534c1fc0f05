#!/bin/sh
# Hard case 32: the GL tests (label gl, tests/CMakeLists.txt) on a second GL implementation,
# Mesa's zink over lavapipe (Debian mesa-vulkan-drivers), a different GLSL-to-SPIR-V path and a
# stricter reading of the spec than llvmpipe; not those labelled browser (they check the HTML
# page) or llvmpipe (about llvmpipe's thread count and OSMesa). Usage: tests/zink.sh
# [BUILD_DIR] [ctest args...] (default build/). Other OSMesa pairings skip themselves with a
# reason (OSMesa has no zink).
# Exits 77 when zink is not available.
set -u
B="${1:-build}"; [ $# -gt 0 ] && shift
export LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=zink
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp/xdg-$(id -un)}"
mkdir -p "$XDG_RUNTIME_DIR" && chmod 700 "$XDG_RUNTIME_DIR"
if ! "$B/src/cli/penumbra" render -W 16 -H 16 --samples 1 -o "$XDG_RUNTIME_DIR/zink-probe.exr" 2>"$XDG_RUNTIME_DIR/zink-probe.err" ||
   ! grep -q "zink" "$XDG_RUNTIME_DIR/zink-probe.err"; then
  echo "zink: no zink context (install mesa-vulkan-drivers): skipped"; cat "$XDG_RUNTIME_DIR/zink-probe.err"; exit 77
fi
grep "renderer:" "$XDG_RUNTIME_DIR/zink-probe.err"
exec ctest --test-dir "$B" --output-on-failure -j2 -L '^gl$' -LE '^(browser|llvmpipe)$' "$@"
