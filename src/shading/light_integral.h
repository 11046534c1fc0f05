// The direct illumination of one light at one surface point, to a target relative standard
// error: multiple importance sampling (Veach 1997, chapter 9) of two strategies, the light's
// stratified samples (sampling/light_samples.h, the same map from the unit square as every
// technique's) and the BRDF's lobes (brdf_sampling.h), combined by the power heuristic (beta 2,
// equal sample counts), with the transmittance of each segment from a caller (the converged
// reference: Embree's; the exact unshadowed term: 1).
//
// Measures: a rect or disk light is integrated over its area (density 1/A for a light sample), a
// sphere light over its volume (density 1/V: the ball of uniformly emitting points of
// light_samples.h, whose radiance along a chord is the emission density 3 L / (4 R) times the
// chord; a BRDF sample hits it at a point uniform on its chord, density p(w) / (chord r^2)).
// A point light is its one sample. Both strategies keep the conventions of the renderer: the
// horizon rule of the geometric normal, the BRDF (shading/shaders/shading.h penumbraBrdf) with the shading normal,
// a one-sided emitter's cosine, the emission texture read at the light point's uv (emissionAt).
//
// Samples come in batches (`batch` of each strategy, a fresh stratified set each, seeded by the
// pixel's seed and the batch index); the batch estimates are independent, so their spread gives
// the standard error of the mean. A pixel stops once it has `minSamples` light samples and its
// radiance's standard error is at most `target` times its largest channel, or at `maxSamples`.
#pragma once

#include <cstdint>
#include <functional>

#include <glm/glm.hpp>

#include "core/image.h"
#include "scene/gbuffer.h"
#include "scene/scene.h"

namespace penumbra::shading {

struct IntegratorOptions {
  int minSamples = 2048;     // light samples per pixel at least (the visibility buffer's)
  int batch = 256;           // samples of each strategy per batch
  int maxSamples = 65536;    // light samples per pixel at most
  double target = 1e-3;      // the radiance's standard error relative to its largest channel
  bool brdfSampling = true;  // false: light samples only (the old converged reference)
  bool lightColour = true;   // false: the radiance without the light's colour and intensity
};

// What one pixel's integral needs: the surface (renderer's G-buffer) and its BRDF inputs.
struct SurfacePoint {
  glm::vec3 p, ng, eye;  // point, geometric normal facing the eye, the eye (or p + ng)
  glm::vec3 origin;      // the shadow rays' start (shared/numerics.h penumbraShadowOrigin)
  bool shaded = false;   // false: visibility only (a G-buffer without BRDF inputs)
  glm::vec3 ns{0.0f}, baseColor{0.0f};
  float metallic = 0.0f, roughness = 1.0f;
  int model = 0;
};

struct PixelEstimate {
  glm::dvec3 visibility{0.0}, visibilityVariance{0.0};  // eq. 2 (light samples) and its mean's variance
  glm::dvec3 radiance{0.0}, radianceVariance{0.0};      // colour * intensity included
  int samples = 0;                                      // light samples (and as many BRDF samples)
  bool capped = false;                                  // stopped at maxSamples short of the target
  std::uint64_t rays = 0;
};

// Transmittances of the segments from `origin` to each of `targets[0..n)` into `out`.
using SegmentTracer = std::function<void(const glm::vec3& origin, const glm::vec3* targets, int n, float* out)>;

class LightIntegrator {
 public:
  // Throws penumbra::Error for a bad light (as makeLightSamples) or bad options.
  LightIntegrator(const Scene& scene, const Light& light, float time, const IntegratorOptions& options);
  PixelEstimate estimate(const SurfacePoint& s, std::uint32_t seed, const SegmentTracer& trace) const;
  const IntegratorOptions& options() const { return o_; }

 private:
  struct Hit {
    glm::dvec3 x;          // the light point
    double density = 0.0;  // of the BRDF strategy in the light's measure, per unit p(w)
  };
  bool hitLight(const glm::dvec3& p, const glm::dvec3& w, double u, Hit& hit) const;
  double brdfToMeasure(const glm::dvec3& p, const glm::dvec3& x) const;
  glm::dvec3 emission(const glm::dvec3& x) const;  // colour * intensity * texture, per the measure

  const Scene& scene_;
  Light light_;
  float time_;
  IntegratorOptions o_;
  glm::dvec3 c_, n_, t_, b_;
  double radius_ = 0.0, density_ = 0.0;  // density: the light strategy's, 1/A or 1/V
  glm::dvec3 scale_{1.0};                // emission per unit texture value (emission())
  const Image* texture_ = nullptr;
};

// The unshadowed term (transmittance 1) of `light` at every surface pixel of `gbuf` (which must
// carry the BRDF inputs), RGB; rows on all cores. What ratio-exact shading uses.
Image unshadowedIntegral(const CpuGBuffer& gbuf, const Scene& scene, const Light& light, float time,
                         const IntegratorOptions& options);

}  // namespace penumbra::shading
