// The global index of a 1D job of PENUMBRA_MAP_LOCAL_SIZE-wide groups dispatched by
// shadow_map::dispatchThreads (maps.h): large jobs
// are split over y because a dispatch holds at most 65535 work groups along x.
#include "techniques/common/shadow_map/shaders/shadow_map_bindings.h"
uint globalIndex() {
  return gl_GlobalInvocationID.y * gl_NumWorkGroups.x * uint(PENUMBRA_MAP_LOCAL_SIZE) + gl_GlobalInvocationID.x;
}
