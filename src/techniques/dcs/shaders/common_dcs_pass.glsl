// The sample range of a dcs counter pass and, for the compute path (dcs_wedge.comp), the solids
// of one dispatch: read from a storage buffer (dcs.cpp writePass), not from uniforms. Mesa 22.3's
// lavapipe (the Vulkan driver under zink) inlines the uniforms a loop or branch depends on and
// compiles a new shader each time the program's uniforms are bound again, at every draw, without
// freeing the one before (lvp_execute.c, update_inline_shader_state): the per-sample loops bounded
// by passCount made a reused renderer's dcs frames grow by 1.2 MiB each on zink
// (render_resources_test, 2026-12-04) and recompiled the wedge shader at every draw. Values read
// from a storage buffer are never inlined.
#ifndef DCS_PASS_GLSL
#define DCS_PASS_GLSL
#include "dcs_bindings.h"

layout(std430, binding = PENUMBRA_SSBO_DCS_PASS) readonly buffer DcsPass {
  uint passFirst;     // first sample of this pass
  uint passCount;     // samples in this pass
  uint solidFirst;    // compute path: this dispatch's solids, [solidFirst, solidEnd) of the range bound
  uint solidEnd;
  int finalDispatch;  // compute path: 1 on the pass's last dispatch (the counts go into the counters)
};

#endif
