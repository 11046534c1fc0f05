// What raytrace-denoised's two denoisers (ours in denoised.cpp, the FidelityFX one in
// ffx_denoiser.cpp) share: rows on all cores, the reprojection of a pixel into the previous
// frame, and the visibility from a denoised shadow ratio.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

#include "core/image.h"
#include "scene/gbuffer.h"
#include "scene/scene.h"
#include "pipeline/technique.h"

namespace penumbra::denoise {

// body(y) for every row on all cores (rows from a shared counter; each pixel depends only on
// its inputs, so the result does not depend on the thread count).
template <class Body>
void forEachRow(int height, Body body) {
  std::atomic<int> next{0};
  auto worker = [&] {
    for (int y = next++; y < height; y = next++) body(y);
  };
  const unsigned threads = std::max(1u, std::min(std::thread::hardware_concurrency(), unsigned(std::max(height, 1))));
  std::vector<std::thread> pool;
  for (unsigned i = 1; i < threads; ++i) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
}

// The previous frame's view: its camera's clip transform and the coordinates its G-buffer was in.
struct PreviousView {
  glm::mat4 clip;
  glm::dvec3 origin{0.0};
};
PreviousView previousView(const Camera& camera, const glm::dvec3& origin, float aspect);

// The pixel of the previous frame (index into its G-buffer of g's size) that pixel i's surface
// point projected to, or -1 (behind the camera or off the image); `p` receives the point in the
// previous frame's coordinates. The disocclusion test is the caller's.
long previousPixel(const CpuGBuffer& g, std::size_t i, const PreviousView& previous, glm::vec3& p);

// The visibility: the ratio (clamped to [0, 1]) times the pixel's unshadowed V over all its N
// samples above the horizon, so that the pipeline's ratio shading gets the ratio back.
Image visibilityFromRatio(const CpuGBuffer& g, const LightSampleSet& set, const Image& ratio);

}  // namespace penumbra::denoise
