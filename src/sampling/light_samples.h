// Light-sample sets: the one source of light-sample positions for every technique and for the
// ray-traced reference, so that per-sample results are comparable (DCS paper section 5, 7.1).
//
// A set is N points on (rect, disk) or in (sphere) the light, in world space. Several sets can
// be made (rotations of the base set for decorrelated sampling; K*K independent sets for
// interleaved sampling); which set a pixel uses is penumbraSetForPixel() of shaders/sample_sets.h,
// identical on CPU and GPU. N == 1 gives the light centre (hard shadows). Fixed seeds: the same
// parameters always give bit-identical sets.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "shared/shared.h"  // NOLINT: shared with GLSL
#include "core/names.h"
#include "scene/scene.h"

namespace penumbra {

enum class SampleStrategy { Stratified, Poisson, Vogel };
enum class PixelPattern { Correlated = 0, Decorrelated = 1, Interleaved = 2 };
static_assert(int(PixelPattern::Correlated) == PENUMBRA_PATTERN_CORRELATED &&
              int(PixelPattern::Decorrelated) == PENUMBRA_PATTERN_DECORRELATED &&
              int(PixelPattern::Interleaved) == PENUMBRA_PATTERN_INTERLEAVED);

struct SamplingParams {
  int count = 16;  // N light samples per light, 1..PENUMBRA_MAX_SAMPLES
  SampleStrategy strategy = SampleStrategy::Stratified;
  PixelPattern pattern = PixelPattern::Correlated;
  int decorrelatedSets = 16;  // M rotated sets for PixelPattern::Decorrelated
  int interleaveK = 4;        // K for PixelPattern::Interleaved (K*K sets)
  std::uint32_t seed = 1;
};

inline constexpr Named<SampleStrategy> kSampleStrategyNames[] = {
    {SampleStrategy::Stratified, "stratified"}, {SampleStrategy::Poisson, "poisson"}, {SampleStrategy::Vogel, "vogel"}};
inline constexpr Named<PixelPattern> kPixelPatternNames[] = {{PixelPattern::Correlated, "correlated"},
                                                             {PixelPattern::Decorrelated, "decorrelated"},
                                                             {PixelPattern::Interleaved, "interleaved"}};
inline const char* toString(SampleStrategy s) { return nameOf(kSampleStrategyNames, s); }
inline const char* toString(PixelPattern p) { return nameOf(kPixelPatternNames, p); }

// Radiometry of a sample (see docs/architecture.md "Lighting pipeline"): a rect/disk sample is a one-sided Lambertian
// patch of area A/N emitting along the light normal; a sphere light is a uniformly emitting
// ball sampled in its volume, each sample an isotropic point of intensity L * pi R^2 / N
// (diverges from a surface-sampled sphere so that eq. 1 needs no per-point weighting); a point
// light is one isotropic sample.
struct LightSampleSet {
  int count = 0;     // N
  int setCount = 1;  // number of sets (M or K*K)
  PixelPattern pattern = PixelPattern::Correlated;
  int interleaveK = 1;
  std::uint32_t seed = 1;
  SampleStrategy strategy = SampleStrategy::Stratified;
  LightShape shape = LightShape::Rect;
  std::vector<glm::vec3> positions;  // world, [set * count + k]
  std::vector<glm::vec2> uv;         // light parametric coords in [0,1]^2, same indexing
  // L_i of eq. 2: emission texture value at the sample (rgb, 1 for untextured lights), same
  // indexing. The light's colour * intensity is applied at shading time.
  std::vector<glm::vec3> luminance;
  glm::vec3 lightNormal{0.0f};  // emission normal for one-sided lights, 0 for isotropic
  // Per-sample emission scale so that sample k contributes
  //   sampleWeight * colour * intensity * L_k * f_r * cos(theta_p) * [cos(theta_l)] / r^2
  // ([cos(theta_l)] only for one-sided lights): A/N for rect/disk, pi R^2 / N for spheres, 1 for
  // points.
  float sampleWeight = 1.0f;

  int setForPixel(int x, int y) const;
  const glm::vec3& position(int set, int k) const { return positions[std::size_t(set) * count + k]; }
};

// Makes the sample sets of `light` at animation time `time` (selects the emission frame).
// Throws penumbra::Error("samples", ...) for count outside 1..PENUMBRA_MAX_SAMPLES and
// penumbra::Error(light.name, ...) for a zero-size area light.
// A point light (count 1) or count == 1 (the centre) collapses to one correlated set: callers
// must use the returned count/setCount/pattern/interleaveK, not the params. Also throws
// Error("decorrelated sets") for decorrelatedSets outside 1..4096 and Error("interleave K") for interleaveK
// outside 1..16 (when that pattern is used), and Error(light.name) for a bad emission texture.
LightSampleSet makeLightSamples(const Scene& scene, const Light& light, const SamplingParams& params,
                                float time = 0.0f);

// One set of `count` points (1..2^20, not limited by PENUMBRA_MAX_SAMPLES) of `strategy` seeded
// by `seed`, mapped onto the light exactly like the base set of makeLightSamples (pattern
// correlated, one set). The converged reference makes a fresh one per pixel. Throws
// penumbra::Error("reference-samples", ...) for a bad count, and like makeLightSamples for the
// light.
LightSampleSet makeLightSampleSet(const Scene& scene, const Light& light, SampleStrategy strategy, int count,
                                  std::uint32_t seed, float time = 0.0f);

// The emission texture of `light` at `time` (its frame at that time), null for an untextured
// light; throws like makeLightSamples for a bad light or texture.
const Image* lightEmissionTexture(const Scene& scene, const Light& light, float time = 0.0f);

// Bilinear RGB of a linear emission texture at light uv, each sample's luminance: texel centres at
// (i + 0.5) / w, clamped to the edge; v = 0 is the image's top row (row 0, the glTF texture
// convention). One- and two-channel textures are grey.
glm::vec3 emissionAt(const Image& texture, glm::dvec2 uv);

// Unit-domain point sets, exposed for tests: N points in [0,1)^2 (stratified: jittered
// sqrt(N) x ceil(N/sqrt(N)) grid; poisson: dart throwing with decreasing radius; vogel:
// golden-angle spiral mapped to the square by the concentric inverse).
std::vector<glm::vec2> unitSquareSamples(SampleStrategy strategy, int count, std::uint32_t seed);

}  // namespace penumbra
