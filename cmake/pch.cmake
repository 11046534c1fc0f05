# Precompiled headers (CMake's target_precompile_headers, force-included into every unit of the
# target): the third-party and standard headers most of a target's units parse. Parsing them was
# 2-5 s of a unit's 5-12 s on the 2-core CI machine (gtest 1.4 s, nlohmann/json 2.2 s, CLI11
# 2.5 s, spdlog 1.3 s, measured 2026-12-06), and CI builds everything twice (normal and
# sanitizers). Never penumbra's own headers: a unit that forgets one of our includes must still
# fail to compile, and the include roots keep holding the layers (cmake/layers.cmake).
set(PENUMBRA_PCH_COMMON <algorithm> <cmath> <functional> <map> <memory> <string> <vector> <glm/glm.hpp>)

# penumbra_precompile(target [headers...]): the common headers and these.
function(penumbra_precompile target)
  target_precompile_headers(${target} PRIVATE ${PENUMBRA_PCH_COMMON} ${ARGN})
endfunction()
