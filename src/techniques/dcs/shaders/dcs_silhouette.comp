// GPU path of the accurate silhouette (geometry/silhouette.h, extractAccurateSilhouette): one
// invocation per edge classifies the light against the planes of the edge's triangles and
// appends the edge when a plane touches or cuts the light or when its multiplicity for the
// whole light is non-zero. Same rule as the CPU path, in float.
#include "dcs_bindings.h"
#include "common_dcs.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = PENUMBRA_SSBO_DCS_STATUS) buffer SilhouetteOut {
  uint edgeCount;
  uint edgeIds[];
};

uniform uint totalEdges;
uniform int lightKind;  // 0 point, 1 rect, 2 disk, 3 sphere (geo::LightExtent::Kind)
uniform vec3 lightCentre;
uniform vec3 lightNormal;
uniform vec3 lightTangent;
uniform vec3 lightBitangent;
uniform vec2 lightHalfSize;  // rect
uniform float lightRadius;   // disk, sphere

int classifyLight(vec3 n, vec3 point) {
  float len = length(n);
  if (!(len > 0.0)) return 0;
  n /= len;
  float centre = dot(n, lightCentre - point);
  float extent = 0.0;
  if (lightKind == 1)
    extent = lightHalfSize.x * abs(dot(n, lightTangent)) + lightHalfSize.y * abs(dot(n, lightBitangent));
  else if (lightKind == 2)
    extent = lightRadius * sqrt(max(0.0, 1.0 - dot(n, lightNormal) * dot(n, lightNormal)));
  else if (lightKind == 3)
    extent = lightRadius;
  return centre > extent ? 1 : (centre < -extent ? -1 : 0);
}

void main() {
  uint id = gl_GlobalInvocationID.x;
  if (id >= totalEdges) return;
  DcsEdge e = dcsEdges[id];
  if (e.meta.w == 0) return;  // a mesh that never occludes (opacity 0)
  bool cut = false;
  int m = 0;
  for (int k = 0; k < e.meta.y; ++k) {
    DcsIncidence t = dcsIncidences[e.meta.x + k];
    int side = classifyLight(t.normal.xyz, e.v0.xyz);
    cut = cut || side == 0;
    int capSign = e.meta.z != 0 ? (side > 0 ? 1 : 0) : side;
    m += capSign * int(t.third.w);  // third.w: the triangle's orientation along the edge
  }
  if (cut || m != 0) edgeIds[atomicAdd(edgeCount, 1u)] = id;
}
