// The compute path's first step: the wedge solid of every selected edge (dcs_solid.glsl), one
// invocation an edge, for dcs_wedge.comp to cull tiles and test points with.
#include "dcs_solid.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = PENUMBRA_SSBO_DCS_EDGE_IDS) readonly buffer DcsEdgeIds { int dcsEdgeIds[]; };
layout(std430, binding = PENUMBRA_SSBO_DCS_SOLIDS) writeonly buffer DcsSolids { DcsSolidPlanes dcsSolids[]; };
uniform uint idFirst;     // this dispatch's first edge in DcsEdgeIds; its solids are the bound range
uniform uint solidCount;  // (compute_wedges.cpp buildSolids)

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= solidCount) return;
  int id = dcsEdgeIds[idFirst + i];
  DcsSolid s = dcsSolid(dcsEdges[id]);
  DcsSolidPlanes out_;
  for (int k = 0; k < 5; ++k) out_.plane[k] = s.plane[k];
  if (s.kind == DCS_SOLID_RECT) out_.plane[0] = s.rect;
  int sides = 0;
  if (s.kind == DCS_SOLID_WEDGE) sides = dcsSidePlanes(dcsEdges[id].v0.xyz, dcsEdges[id].v1.xyz, out_.side);
  else
    for (int k = 0; k < DCS_SIDE_PLANES; ++k) out_.side[k] = vec4(0.0);
  out_.meta = ivec4(s.kind, id, sides, 0);
  if (s.kind == DCS_SOLID_RECT) PROFILE_COUNT(profRectangleEdges);
  if (s.kind == DCS_SOLID_WEDGE || s.kind == DCS_SOLID_PYRAMID) PROFILE_COUNT(profWedgeEdges);
  dcsSolids[i] = out_;
}
