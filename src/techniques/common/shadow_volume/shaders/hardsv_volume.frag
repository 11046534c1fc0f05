// Z-fail count into a float target by additive blending (not the 8-bit stencil, which wraps):
// each volume face the view ray meets beyond the visible point adds its weight, negated where the
// face is seen from its front. The sum is the winding number of the visible point, i.e. the
// number of volumes containing it.
// The point is the visible point moved towards the camera along the view ray, off its surface by
// penumbraSurfaceEpsilon (shared/numerics.h penumbraShadowOrigin, where the wedge pass and the reference
// evaluate too): a face through the surface (the point's own near cap; a side in the plane of a
// face edge-on to the light, hard case 9) then lies on the camera's side.
// Whether the ray meets the face, and where, is decided exactly in volume_count.h ("Which faces of the
// shadow volumes the view ray meets"): for a side, "beyond the point" is penumbraSideOfEdgePlane,
// bit for bit the decision dcs's wedges take for the sign of their update, so a point within
// rounding of a side plane gets the integration constant and the wedge updates from the same
// decision. Each face is drawn as its cover (techniques/shadow_volume/volume_cover.h: grown on
// screen, one fragment a pixel) for this test to decide on.
#include "shared/numerics.h"
#include "techniques/common/shadow_volume/shaders/volume_count.h"

layout(binding = PENUMBRA_UNIT_GBUF_POSITION) uniform sampler2D gPosition;
layout(binding = PENUMBRA_UNIT_GBUF_NORMAL) uniform sampler2D gNormal;
uniform vec3 lightPosition;
uniform vec3 eyePosition;

// Per face: (a, weight), (b, kind), (c, 0): a side's edge (v0, v1) in the edge's own order and
// its weight m_e times the mesh's units; a cap's triangle (a, b, c) turned to face the light.
layout(std430, binding = PENUMBRA_SSBO_VOLUME_FACES) readonly buffer VolumeFaces { vec4 faces[]; };
flat in uint vFace;
out float outCount;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 gp = texelFetch(gPosition, px, 0);
  if (gp.w == 0.0) discard;
  vec3 o = penumbraShadowOrigin(gp.xyz, texelFetch(gNormal, px, 0).xyz, eyePosition);
  precise vec3 d = o - eyePosition;
  vec4 a = faces[3u * vFace], b = faces[3u * vFace + 1u], c = faces[3u * vFace + 2u];
  float count = 0.0;
  if (int(b.w) == PENUMBRA_VOLUME_SIDE) {
    precise vec3 n = cross(d, o - lightPosition);
    count = penumbraSideCount(a.xyz, b.xyz, a.w, lightPosition, o, d, n);
  } else if (int(b.w) == PENUMBRA_VOLUME_NEAR_CAP) {
    count = penumbraNearCapCount(a.xyz, b.xyz, c.xyz, a.w, o, d);
  } else {
    count = penumbraFarCapCount(a.xyz, b.xyz, c.xyz, a.w, lightPosition, d);
  }
  if (count == 0.0) discard;
  outCount = count;
}
