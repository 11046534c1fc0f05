// CPU ray-traced reference with Embree 3. No GL.
//
// Mode "same samples": for every pixel of the G-buffer and every light sample of the pixel's
// set, the transmittance of the segment from the surface point to the sample (opaque hit -> 0,
// semi-opaque surfaces multiply their (1 - opacity)). Mode "converged": the visibility buffer
// from many stratified light samples per pixel, decorrelated, and the shaded image by multiple
// importance sampling of the light and the BRDF to a target standard error
// (shading/light_integral.h), each with its own noise: the converged truth compare measures
// every technique's shaded image against.
//
// Conventions shared with every GPU technique (so that results are comparable):
//  * a pixel is shaded only if the G-buffer has a surface there (valid);
//  * a sample below the surface's horizon, dot(n, x_k - p) <= 0 with n the camera-facing
//    normal, has visibility 0;
//  * the ray starts at penumbraShadowOrigin(p, n, camera) (shared/numerics.h: p moved towards
//    the camera along the view ray until penumbraSurfaceEpsilon(p), 2^-15 of p's largest
//    coordinate, off its surface; along n when the G-buffer has no camera) and stops at the
//    sample (t < 1 - 1e-5 relative).
//  * positions are camera-relative (Scene::cameraRelative; the pipeline's Renderer hands every
//    technique and this reference the same translated scene), so that floats keep the detail
//    of a scene far from the world's origin.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "core/image.h"
#include "sampling/light_samples.h"
#include "scene/gbuffer.h"
#include "scene/scene.h"
#include "shading/light_integral.h"

namespace penumbra {

// Per-light visibility: the RGB visibility buffer of eq. 2 (textured lights weight each sample by
// its L_i) and, when available, per-(pixel, sample) transmittance [pixel * N + k].
struct VisibilityResult {
  Image visibility;              // RGB, width x height
  std::vector<float> perSample;  // empty or width*height*N
  int samples = 0;               // N
  // Converged mode with a G-buffer that carries the BRDF inputs: the light's outgoing radiance
  // (RGB, width x height); else empty.
  Image radiance;
  // Converged mode: the variance of each pixel's estimate (the square of its standard error,
  // from the spread of its independent batches) of the visibility and of the radiance (empty
  // without radiance); light samples per pixel, their mean over surface pixels, their largest
  // count, and the pixels that stopped at the cap short of the target.
  Image visibilityVariance, radianceVariance;
  double meanSamples = 0.0;
  int maxSamples = 0;
  std::int64_t cappedPixels = 0;
};

// Sparse mode (raytrace-denoised): a few of each pixel's samples, their shadow ratio and the
// distance to their occluders, the noisy input of a denoiser.
struct SparseResult {
  // Per pixel: sum_j L_kj T_kj / sum_j L_kj over the traced samples (those above the horizon),
  // RGB; 1 where none was traced (the shading's unshadowed term is then 0 anyway).
  Image ratio;
  std::vector<float> blocker;  // the mean distance to the nearest occluder over the blocked rays; 0: none blocked
  int rays = 0;                // rays per pixel at most (spp)
};

class EmbreeReference {
 public:
  // Builds the BVH over all scene meshes (opacity per mesh from its material). Throws
  // penumbra::Error on an Embree device error.
  explicit EmbreeReference(const Scene& scene, int threads = 0 /* 0 = all cores */);
  ~EmbreeReference();
  EmbreeReference(const EmbreeReference&) = delete;
  EmbreeReference& operator=(const EmbreeReference&) = delete;

  // Same-samples mode.
  VisibilityResult sameSamples(const CpuGBuffer& gbuf, const LightSampleSet& samples) const;

  // Converged mode: per pixel, batches of fresh stratified light samples (and BRDF samples,
  // where the G-buffer has the BRDF inputs) until the options' target or cap (seeded by the
  // pixel; `seed` != 0 gives an independent estimate). Throws penumbra::Error for bad options.
  VisibilityResult converged(const CpuGBuffer& gbuf, const Light& light, const Scene& scene,
                             const shading::IntegratorOptions& options = {}, float time = 0.0f,
                             std::uint32_t seed = 0) const;

  // Sparse mode: `spp` of the M samples of each pixel's set above its horizon, those
  // (h + rotation + j) mod M for j < spp with h a hash of the pixel index (raising `rotation` by
  // spp each frame visits every one once in M / spp frames); none when M is 0.
  SparseResult sparseSamples(const CpuGBuffer& gbuf, const LightSampleSet& samples, int spp,
                             std::uint32_t rotation) const;

  // Transmittance of one segment (for tests): 1 unoccluded, 0 opaque hit.
  float transmittance(const glm::vec3& from, const glm::vec3& to) const;

  double raysCast() const;  // total rays cast since construction (for rays/s)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace penumbra
