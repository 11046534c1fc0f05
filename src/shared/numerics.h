// Numerics both languages must decide alike: the surface epsilon and shadow-ray origin every
// technique and the reference evaluate visibility at, and the integer hash. Valid in C++ and
// GLSL (shared/shared.h); C++ includes it through shared/shared.hpp.
#ifndef PENUMBRA_NUMERICS_H
#define PENUMBRA_NUMERICS_H

#include "shared/shared.h"

// Integer hash (PCG output permutation); identical in C++ and GLSL.
PENUMBRA_FN uint penumbraHash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// How far off its surface visibility is evaluated for a point p, relative to p's own floating-
// point magnitude, never to the scene's size (Waechter and Binder, "A Fast and Robust Method for
// Avoiding Self-Intersection", Ray Tracing Gems 2019, ch. 6: an offset of 256 ULPs of the point's
// coordinates, a fixed tiny offset near the origin). We use the largest coordinate for all three
// axes (one distance along the view ray below, not one integer offset per axis) and keep their
// 256 ULPs = 2^-15 relative. Points are in camera-relative coordinates (Scene::cameraRelative),
// so the magnitude is the distance to the camera (at least zNear / sqrt 3 for a visible point)
// and a scene translated anywhere gives the same offset; a scaled scene gets a scaled offset, bit
// for bit at powers of two; a mirrored one the same (absolute values). Divergence: their fixed
// offset near the origin (magnitudes below 1/32 counted as 1/32, which we had) made a world in
// millimetres differ from the same world in metres (hard case 36: the cube scene at 2^-13 off at
// 30 of 4096 values, at 2^-20 at 207); near the camera a visible point cannot be, so the floor is
// 2^-100, there only to keep the offset positive at a CPU G-buffer's world origin.
#define PENUMBRA_EPS_RELATIVE (1.0f / 32768.0f)
#define PENUMBRA_EPS_ORIGIN 7.88860905e-31f  // 2^-100 (no hex floats in GLSL)
PENUMBRA_FN float penumbraSurfaceEpsilon(vec3 p) {
  float m = max(max(abs(p.x), abs(p.y)), max(abs(p.z), PENUMBRA_EPS_ORIGIN));
  return m * PENUMBRA_EPS_RELATIVE;
}

// Where visibility is evaluated for a visible point p (unit normal n facing the camera, camera
// at `eye`): p moved towards the camera along the view ray until it is penumbraSurfaceEpsilon(p)
// off its surface, at most PENUMBRA_ORIGIN_MAX_STRETCH times that along the ray (grazing views).
// The reference starts its shadow rays there, and the shadow-volume count and the dcs wedges
// evaluate their plane tests there: on the view ray, so that what the rasteriser found along
// that ray (which volume face the ray meets, near a face's border too) holds for the point (an
// origin moved along the normal instead left a pixel of hard case 19 off by one, where the ray
// passes within 1e-5 of the box's bottom edge). Without a camera (CPU-only G-buffers),
// eye = p + n.
#define PENUMBRA_ORIGIN_MAX_STRETCH 16.0f
PENUMBRA_FN vec3 penumbraShadowOrigin(vec3 p, vec3 n, vec3 eye) {
  PENUMBRA_PRECISE vec3 v = normalize(eye - p);
  PENUMBRA_PRECISE float along = penumbraSurfaceEpsilon(p) / max(dot(n, v), 1.0f / PENUMBRA_ORIGIN_MAX_STRETCH);
  PENUMBRA_PRECISE vec3 o = p + v * along;
  return o;
}

#endif
