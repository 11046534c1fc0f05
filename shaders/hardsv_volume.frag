// Z-fail count into a float target by additive blending (not the 8-bit stencil, which wraps):
// a volume face counts where the view ray meets it behind the visible point; leaving the
// volume (back face towards the camera) adds the weight, entering it subtracts. The sum is the
// winding number of the visible point, i.e. the number of volumes containing it.
// "Behind" is decided by a plane test, not by the depth buffer: the ray from the camera through
// the point meets the face's plane beyond the point exactly when the point and the camera lie
// on the same side of that plane (the rasteriser has already found that the ray meets the face,
// in front of the camera). The point is the visible point moved towards the camera along the
// view ray, off its surface by penumbraSurfaceEpsilon (shared.h penumbraShadowOrigin, where
// the wedge pass and the reference evaluate too): a face through the surface (the point's own near cap; a side in the plane of a face edge-on to
// the light, hard case 9) then counts as on the camera's side. For a side, the test is
// sideOfEdgePlane (common_volume.glsl), bit for bit the one the dcs wedges use to choose the sign of their
// update, so a point within rounding of a side plane gets the integration constant and the
// wedge updates from the same decision (a depth test with polygon offset left a few pixels on
// the light centre's hard-shadow boundary off by one).
#include "common_volume.glsl"

layout(binding = PENUMBRA_UNIT_GBUF_POSITION) uniform sampler2D gPosition;
layout(binding = PENUMBRA_UNIT_GBUF_NORMAL) uniform sampler2D gNormal;
uniform vec3 lightPosition;
uniform vec3 eyePosition;

#ifdef SIDES
flat in vec3 gEdgeV0, gEdgeV1;
#else
flat in vec4 gPlane;
#endif
flat in float gWeight;
flat in int gEyeSide;
out float outCount;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 gp = texelFetch(gPosition, px, 0);
  if (gp.w == 0.0) discard;
  vec3 p = penumbraShadowOrigin(gp.xyz, texelFetch(gNormal, px, 0).xyz, eyePosition);
#ifdef SIDES
  int side = sideOfEdgePlane(gEdgeV0, gEdgeV1, lightPosition, p);
#else
  // Far cap (gEyeSide == 0): at infinity, behind every point.
  int side = gEyeSide == 0 ? 0 : (dot(gPlane.xyz, p) + gPlane.w >= 0.0 ? 1 : -1);
#endif
  if (side != gEyeSide) discard;
  outCount = gl_FrontFacing ? -gWeight : gWeight;
}
