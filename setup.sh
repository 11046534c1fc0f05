#!/bin/sh
# Quick start, step 1 (as root on Debian 12): install the Debian packages penumbra needs, build,
# and run the main job: the default textured-area-light scene with every technique and the
# Embree reference, written to out/default/ (images, heat maps, report.json), then the glossy
# shading scene to out/glossy/.
#   ./setup.sh          install + build + main job
#   ./setup.sh --deps   install the packages only (used by .ci/run)
# Slurm, munge and GNU parallel are for the study tests (tests/study_run_test.sh), which start
# daemons of their own on localhost with a configuration of their own.
set -eu
cd "$(dirname "$0")"
PACKAGES="cmake ninja-build g++ pkg-config
  libegl-dev libegl-mesa0 libgl1-mesa-dri libopengl-dev libosmesa6-dev
  libglm-dev libopenmesh-dev libtinygltf-dev libdraco-dev libmeshoptimizer-dev libopenexr-dev libimath-dev libembree-dev
  libcli11-dev nlohmann-json3-dev libspdlog-dev libfmt-dev libpng-dev
  libgtest-dev libgmock-dev libbenchmark-dev assimp-testmodels chromium
  mesa-vulkan-drivers clang-format
  slurm-wlm munge parallel"
missing=""
for p in $PACKAGES; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -q
  # shellcheck disable=SC2086
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends $missing
fi
[ "${1:-}" = "--deps" ] && exit 0
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo
cmake --build build
mkdir -p out
./build/src/cli/penumbra compare --techniques all --samples 16 -o out/default
# The shading scene (glossy metallic-roughness materials, smooth normals, three lights):
# every shaded image also measured against the converged shaded reference.
./build/src/cli/penumbra compare scenes/glossy.json --techniques dcs,hard-sv,mvr,pcss,vssm --samples 16 \
  --converged -o out/glossy
