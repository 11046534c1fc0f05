#include "techniques/denoised/filtering.h"

#include <cmath>

#include "pipeline/renderer.h"

namespace penumbra::denoise {

PreviousView previousView(const Camera& camera, const glm::dvec3& origin, float aspect) {
  return {clipFromViewReversedInfinite(camera, aspect) * viewFromWorld(camera), origin};
}

long previousPixel(const CpuGBuffer& g, std::size_t i, const PreviousView& previous, glm::vec3& p) {
  p = g.position[i] + glm::vec3(g.origin - previous.origin);  // this frame's coordinates into the last one's
  const glm::vec4 c = previous.clip * glm::vec4(p, 1.0f);
  if (!(c.w > 0.0f)) return -1;
  // The G-buffer's rows are top row first (scene/gbuffer.h): ndc y = 1 is row 0. Range checked
  // as floats before the conversion (a point near the camera plane projects far).
  const float fx = std::floor((c.x / c.w * 0.5f + 0.5f) * float(g.width));
  const float fy = std::floor((0.5f - c.y / c.w * 0.5f) * float(g.height));
  if (!(fx >= 0.0f && fy >= 0.0f && fx < float(g.width) && fy < float(g.height))) return -1;
  return long(fy) * long(g.width) + long(fx);
}

Image visibilityFromRatio(const CpuGBuffer& g, const LightSampleSet& set, const Image& ratio) {
  const int n = set.count;
  Image visibility(g.width, g.height, 3, 0.0f);
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const std::size_t i = std::size_t(y) * g.width + x;
      if (!g.valid[i]) continue;
      const std::size_t first = std::size_t(set.setForPixel(x, y)) * std::size_t(n);
      glm::vec3 unshadowed(0.0f);
      for (int k = 0; k < n; ++k)
        if (glm::dot(g.normal[i], set.positions[first + k] - g.position[i]) > 0.0f)
          unshadowed += set.luminance[first + k];
      unshadowed /= float(n);
      for (int c = 0; c < 3; ++c) visibility.at(x, y, c) = std::clamp(ratio.at(x, y, c), 0.0f, 1.0f) * unshadowed[c];
    }
  return visibility;
}

}  // namespace penumbra::denoise
