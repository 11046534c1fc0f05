// The VWSS point buffer (src/techniques/vwss): a count, then xyz world positions, 3 floats each
// (the paper's 32-bit float points, section 3.1).
#include "shadow_map_bindings.h"
layout(std430, binding = PENUMBRA_SSBO_POINTS) buffer Points {
  uint pointCount;  // points generated (may exceed the capacity: then the pass is rerun)
  uint pointPad0, pointPad1, pointPad2;
  float pointData[];
};
uniform uint pointCapacity;

vec3 loadPoint(uint i) { return vec3(pointData[3u * i], pointData[3u * i + 1u], pointData[3u * i + 2u]); }
