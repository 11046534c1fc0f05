// Where the shadow-volume count draws a volume face (src/techniques/common/shadow_volume/shaders/hardsv_volume.frag): a
// convex polygon on screen holding every pixel centre whose view ray may meet the face. The fragment shader decides
// exactly whether the ray meets it (shaders/volume_count.h, "Which faces of the shadow volumes the view ray meets");
// the rasteriser only has to hand it each such pixel once. So a face is drawn grown by a margin, as one convex fan: no
// pixel gets two of its fragments (but within rounding of the cover's border, a margin away from the face, where the
// exact test refuses it), and none whose ray may meet it is missed: the margin, coverMargin(), is three times the
// rasteriser's snapping of window coordinates (2^-GL_SUBPIXEL_BITS pixel: llvmpipe 8 bits, the
// GL asks for 4) and far above the rounding here. Drawn with no margin, the engine scene at
// 128 px had 473 pixels wrong: the exact test and the rasteriser disagree along every edge.
// Each pixel of margin costs fragments along the faces' borders (side quads are long and thin:
// 0.25 px tripled the engine's fragments), so it is kept that small.
// Built on the CPU in double: a geometry shader doing the same clipping cost llvmpipe 0.78 s a
// frame on the engine scene, this about 50 ms.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace penumbra {

struct CoverView {
  glm::dmat4 clipFromWorld{1.0};
  glm::dvec2 viewport{0.0};  // pixels
  double clipNear = 0.0;     // half the camera's near distance (see appendCover)
  glm::dvec3 light{0.0};     // where points at infinity are seen from
  double margin = 0.0;       // pixels: coverMargin()
  // Pixels a radian subtends at the centre of the view (the projection's x scale times half the
  // width): turns the float rounding of the fragment shader's decisions into pixels.
  double focalPixels = 0.0;
};

// Three times the snapping of window coordinates, 2^-subpixelBits pixel (at least 4 bits).
// A face grows further where the fragment shader's float decisions about it are less precise
// than that: they are exact functions of float inputs, but a decision about a face whose points
// lie R from the eye (in the camera-relative coordinates every position is in) rounds by about
// 2^-24 R in distance, 2^-24 R / L in angle at a crossing L from the eye; the margin takes 16
// times that, at the face's nearest point on screen (a floor 5e4 wide under a camera 3 above it:
// about 7 pixels; a face of an ordinary scene: 1e-3 pixel, below the snapping).
double coverMargin(int subpixelBits);

// Appends to `out` the cover of the face with `n` corners in order (n <= 4), each a world point
// (w = 1) or a point at infinity in direction xyz - light (w = 0), as window coordinates
// (gl_FragCoord.xy: y turned over, the context's glClipControl(GL_UPPER_LEFT)), counter-
// clockwise; returns how many (0: nothing on screen, or no pixel centre inside). The face is
// clipped to depth >= clipNear (the plane w >= clipNear h in clip coordinates and the world
// homogeneous h, exact for points at infinity and on the way to them: the count only takes
// crossings beyond the visible point, which lies beyond the near plane) and to the guard band
// |x|, |y| <= 2 w. A depth threshold on the homogeneous w alone dropped a floor's far cap wherever
// its directions, nearly opposite across the light's foot, interpolate through short vectors
// (the cube on the 1e5 floor of hard case 25: 10,162 pixels).
std::size_t appendCover(const CoverView& view, const glm::dvec4* corners, int n, std::vector<glm::vec2>& out);

}  // namespace penumbra
