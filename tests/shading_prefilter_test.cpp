// Textured rect and disk lights' unshadowed term: the
// prefiltered emission (Heitz et al. 2016 section 5.3; src/shading/prefiltered_light.h, shading/shaders/shading.h
// penumbraPrefilterFootprint) times the closed-form integral of the lobe, against the integral
// over the texture by quadrature, beside the sum over 16 light samples the renderer would
// otherwise use. GL-free: the GPU reads the same chain with the same coordinates.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "core/image_io.h"
#include "sampling/light_samples.h"
#include "shading/shading_shared.hpp"
#include "shading/ltc.h"
#include "shading/prefiltered_light.h"

namespace penumbra::test {
namespace {

// A checker of 8 x 8 cells, 1 and 0.05 (a high-contrast texture), 64 px.
Image checker() {
  Image img(64, 64, 3);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = ((x / 8 + y / 8) % 2) ? 1.0f : 0.05f;
  return img;
}

struct Config {
  const char* name;
  LightShape shape;
  double height, tilt;  // light centre above the floor; rotation of its normal about the x axis
  double roughness;     // 0: the Lambertian (diffuse) term; else the GGX lobe's (F = 1)
};

// Relative RMSE (over points and channels, relative to the truth's mean) of the term by: the
// prefiltered chain as the renderer reads it (mixture), the paper's one level (single), 16 light
// samples (sampled), and the renderer's whole term with the closed form / LTC integral (whole).
struct Errors {
  double mixture = 0.0, single = 0.0, sampled = 0.0, whole = 0.0;
  int values = 0;
};

// One light over a floor (y = 0, normal +y) seen from an eye above it: for points on a 9 x 9 grid
// under and around the light, the term by quadrature (the texture bilinear as the samples read it,
// 192^2 points on the light), by the prefiltered chain, and by the 16 samples of the interleaved
// set that point would get.
Errors measure(const Image& texture, const Config& k) {
  Scene scene;
  scene.textures.push_back({"texture", texture});
  Light light;
  light.name = "light";
  light.shape = k.shape;
  light.position = {0.0f, float(k.height), 0.0f};
  light.normal = glm::vec3(0.0f, -std::cos(k.tilt), std::sin(k.tilt));
  light.tangent = {1.0f, 0.0f, 0.0f};
  light.size = k.shape == LightShape::Rect ? glm::vec2(1.6f, 1.6f) : glm::vec2(0.8f);
  light.emissionFrames = {0};
  scene.lights.push_back(light);
  SamplingParams params;
  params.count = 16;
  params.pattern = PixelPattern::Interleaved;
  const LightSampleSet samples = makeLightSamples(scene, light, params);
  const shading::PrefilteredLight chain = shading::prefilterLight(texture, k.shape == LightShape::Disk);

  const glm::dvec3 t(light.tangent), b(light.bitangent()), n(light.normal), c(light.position);
  const glm::vec2 half = k.shape == LightShape::Rect ? light.size * 0.5f : glm::vec2(light.size.x);
  const glm::vec3 eye(0.0f, 2.5f, 4.0f);
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  const bool glossy = k.roughness > 0.0;
  const float alpha = shared::penumbraAlpha(float(k.roughness));
  const shading::LtcTable& table = shading::builtinLtcTable();
  const int m = 192;
  Errors e;
  double sumMixture = 0.0, sumSingle = 0.0, sumSampled = 0.0, sumWhole = 0.0, sumTruth = 0.0;
  for (int gz = 0; gz < 9; ++gz)
    for (int gx = 0; gx < 9; ++gx) {
      const glm::vec3 p(float(-2.0 + 0.5 * gx), 0.0f, float(-2.0 + 0.5 * gz));
      if (!(glm::dot(glm::dvec3(p) - c, n) > 0.0)) continue;  // behind the light
      const glm::vec3 v = glm::normalize(eye - p);
      // The lobe towards light point x (per solid angle, times cos(theta_l) / r^2: per area).
      auto lobe = [&](const glm::dvec3& x) {
        const glm::vec3 d = glm::vec3(x) - p;
        const float r2 = glm::dot(d, d);
        const glm::vec3 l = d / std::sqrt(r2);
        const float emitter = std::max(-glm::dot(glm::vec3(n), l), 0.0f);
        if (!glossy) return double(shared::penumbraSampleGeometry(p, up, up, glm::vec3(x), glm::vec3(n)));
        return double(shared::penumbraGgxCosine(up, v, l, alpha)) * emitter / r2;
      };
      glm::dvec3 truth(0.0);
      double plain = 0.0;
      const double cell = (2.0 * half.x / m) * (2.0 * half.y / m);
      for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) {
          const glm::dvec2 uv((i + 0.5) / m, (j + 0.5) / m);
          if (k.shape == LightShape::Disk && glm::dot(uv - 0.5, uv - 0.5) > 0.25) continue;
          const glm::dvec3 x = c + (2.0 * uv.x - 1.0) * double(half.x) * t + (2.0 * uv.y - 1.0) * double(half.y) * b;
          const double w = lobe(x) * cell;
          truth += w * glm::dvec3(emissionAt(texture, uv));
          plain += w;
        }
      if (!(plain > 0.0)) continue;
      // The closed-form (Lambert) or LTC integral of the untextured light and the prefiltered L_D.
      const float nv = glm::dot(up, v);
      const glm::vec4 minv = glossy ? shading::ltcLookup(table, 0, float(k.roughness), nv) : glm::vec4(1, 0, 0, 1);
      const float norm = glossy ? shading::ltcLookup(table, 1, float(k.roughness), nv).x : 1.0f;
      const glm::vec2 polygon =
          shared::penumbraLightPolygon(k.shape == LightShape::Rect ? PENUMBRA_LIGHT_RECT : PENUMBRA_LIGHT_DISK, p, up,
                                       up, glm::vec3(c), glm::vec3(t), glm::vec3(b), half, glossy, v, minv);
      const double closed = glossy ? double(polygon.y) * norm : double(polygon.x);
      const glm::vec3 x = shared::penumbraLtcTangent(up, v), y = glm::cross(up, x);
      const glm::vec3 foot =
          shared::penumbraPrefilterFootprint(p, glm::vec3(c), glm::vec3(t), glm::vec3(b),
                                             k.shape == LightShape::Rect ? half : glm::vec2(half.x), x, y, up, minv);
      const glm::dvec3 filtered(shading::prefilteredEmission(chain, foot));
      // The paper's one level at a log of the footprint, sigma = 0.85 d (the Gaussian with the
      // cosine's half-weight radius d), linear between levels.
      const float level = std::clamp(std::log2(0.85f * foot.z / chain.sigma0), 0.0f, float(chain.levels - 1));
      const int k0 = int(level), k1 = std::min(k0 + 1, chain.levels - 1);
      const glm::dvec3 single(glm::mix(glm::vec3(shading::prefilteredLevel(chain, glm::vec2(foot), k0)),
                                       glm::vec3(shading::prefilteredLevel(chain, glm::vec2(foot), k1)),
                                       level - float(k0)));
      // The 16 samples of the set this grid point would get.
      const int set = samples.setForPixel(gx, gz);
      glm::dvec3 sampled(0.0);
      for (int s = 0; s < samples.count; ++s) {
        const glm::dvec3 xs(samples.position(set, s));
        sampled += lobe(xs) * glm::dvec3(samples.luminance[std::size_t(set) * samples.count + s]);
      }
      sampled *= double(samples.sampleWeight);
      // The quadrature's untextured integral times L_D measures L_D alone (the LTC's own error
      // is Ltc.PolygonIntegralAgainstTheTrueLobe's); `whole` has the closed form's.
      auto squared = [&](const glm::dvec3& a) { return glm::dot(a - truth, a - truth); };
      sumMixture += squared(plain * filtered);
      sumSingle += squared(plain * single);
      sumSampled += squared(sampled);
      sumWhole += squared(closed * filtered);
      sumTruth += truth.x + truth.y + truth.z;
      e.values += 3;
    }
  const double mean = sumTruth / e.values;
  auto relative = [&](double sum) { return std::sqrt(sum / e.values) / mean; };
  e.mixture = relative(sumMixture), e.single = relative(sumSingle);
  e.sampled = relative(sumSampled), e.whole = relative(sumWhole);
  return e;
}

}  // namespace

// The stained-glass window (scenes/textures, saturated colours) and a checker of 8 x 8 cells as
// rect and disk lights over a Lambertian and a glossy floor (F = 1), near (0.6), mid (1.5) and
// far (3), facing the floor or tilted by 0.6 rad. The chain's error is 3.5 to over 100 times
// below 16 samples' noise; facing the floor, where the mixture is the cosine's exact footprint,
// it is within 1.3% and 4-8 times below the paper's one level; with the glossy lobe and the
// tilted light (whose footprint is not centred on the foot point) up to 27% on the stained glass
// (a highlight is one peak per light: a small relative error of L_D there is a large share of
// the RMSE), where one level is sometimes better (roughness 0.6, tilted). Gates at the measured
// values, the worst of the two textures per configuration (printed).
TEST(PrefilteredLight, AgainstTheIntegralOverTheTexture) {
  const Image glass = readPng(std::string(PENUMBRA_SOURCE_DIR) + "/scenes/textures/stained-glass.png");
  const Image board = checker();
  struct Gated {
    Config config;
    double gate;  // on the mixture's relative RMSE
  };
  const Gated configs[] = {
      {{"rect, near, diffuse", LightShape::Rect, 0.6, 0.0, 0.0}, 0.016},
      {{"rect, 1.5, diffuse", LightShape::Rect, 1.5, 0.0, 0.0}, 0.008},
      {{"rect, 3, diffuse", LightShape::Rect, 3.0, 0.0, 0.0}, 0.006},
      {{"rect, 1.5, tilted, diffuse", LightShape::Rect, 1.5, 0.6, 0.0}, 0.09},
      {{"disk, 1.5, diffuse", LightShape::Disk, 1.5, 0.0, 0.0}, 0.007},
      {{"rect, 1.5, roughness 0.3", LightShape::Rect, 1.5, 0.0, 0.3}, 0.3},
      {{"rect, 1.5, roughness 0.6", LightShape::Rect, 1.5, 0.0, 0.6}, 0.09},
      {{"rect, 3, roughness 0.3", LightShape::Rect, 3.0, 0.0, 0.3}, 0.15},
      {{"disk, 1.5, roughness 0.3", LightShape::Disk, 1.5, 0.0, 0.3}, 0.33},
  };
  for (const Image* tex : {&glass, &board})
    for (const Gated& g : configs) {
      const Config& k = g.config;
      const Errors e = measure(*tex, k);
      std::printf(
          "%-13s %-27s relative RMSE: prefiltered %.4f (one level %.4f, with the closed form %.4f), "
          "16 samples %.4f\n",
          tex == &glass ? "stained-glass" : "checker", k.name, e.mixture, e.single, e.whole, e.sampled);
      EXPECT_GE(e.values, 3 * 60);
      EXPECT_LE(e.mixture, g.gate) << k.name;
      EXPECT_LE(e.mixture, 0.35 * e.sampled) << k.name << ": well below 16 samples' noise";
      if (k.roughness == 0.0 && k.tilt == 0.0) {
        EXPECT_LE(e.mixture, e.single) << k.name << ": the mixture's reason";
      }
    }
}

// The chain of a constant emission is that constant at every level and every point of the margin
// (the normalised convolution: nothing fades at the light's border), and its weight channel is 1
// deep inside and falls off outside; the finest level reproduces a checker inside its cells.
TEST(PrefilteredLight, TheChainIsANormalisedConvolution) {
  Image flat(16, 16, 3, 0.0f);
  for (int i = 0; i < 16 * 16; ++i)
    flat.data[std::size_t(i) * 3] = 0.3f, flat.data[std::size_t(i) * 3 + 1] = 0.6f,
                               flat.data[std::size_t(i) * 3 + 2] = 0.9f;
  for (bool disk : {false, true}) {
    const shading::PrefilteredLight chain = shading::prefilterLight(flat, disk);
    EXPECT_GE(chain.levels, 6);
    EXPECT_GE(chain.sigma0 * std::exp2(float(chain.levels - 1)), 2.0f);
    double worst = 0.0;
    for (const glm::vec4& t : chain.texels)
      worst = std::max(worst, double(glm::length(glm::vec3(t) - glm::vec3(0.3f, 0.6f, 0.9f))));
    EXPECT_LE(worst, 1e-5) << (disk ? "disk" : "rect");
    EXPECT_NEAR(shading::prefilteredLevel(chain, glm::vec2(0.5f), 0).w, 1.0f, 1e-5f);
    EXPECT_LT(shading::prefilteredLevel(chain, glm::vec2(-0.2f, 0.5f), 0).w, 1e-3f);
  }
  const Image board = checker();
  const shading::PrefilteredLight chain = shading::prefilterLight(board, false);
  for (glm::vec2 uv : {glm::vec2(0.0625f, 0.0625f), glm::vec2(0.1875f, 0.0625f), glm::vec2(0.3125f, 0.4375f)}) {
    const glm::vec3 expected = emissionAt(board, glm::dvec2(uv));
    EXPECT_LE(glm::length(glm::vec3(shading::prefilteredLevel(chain, uv, 0)) - expected), 0.02f * glm::length(expected))
        << uv.x << ", " << uv.y;
  }
}

// The footprint of a light facing the point: the projection's uv and d = distance / sqrt(area),
// for a point under the light's corner at distance 2 from a 1 x 0.5 rect (identity M^-1, any frame).
TEST(PrefilteredLight, TheFootprintOfAFacingLight) {
  const glm::vec3 centre(0.0f, 2.0f, 0.0f), tangent(1.0f, 0.0f, 0.0f), bitangent(0.0f, 0.0f, 1.0f);
  const glm::vec3 p(0.5f, 0.0f, -0.25f);  // under the corner uv (1, 0)
  const glm::vec3 foot =
      shared::penumbraPrefilterFootprint(p, centre, tangent, bitangent, glm::vec2(0.5f, 0.25f), glm::vec3(0, 0, 1),
                                         glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
  EXPECT_NEAR(foot.x, 1.0f, 1e-6f);
  EXPECT_NEAR(foot.y, 0.0f, 1e-6f);
  EXPECT_NEAR(foot.z, 2.0f / std::sqrt(0.5f), 1e-5f);
  // The weights over the levels sum to 1 (a distribution over the mixture's scales).
  for (float d : {0.01f, 0.3f, 5.0f}) {
    float sum = 0.0f;
    for (int k = 0; k < 8; ++k) sum += shared::penumbraPrefilterWeight(d, 0.015f, k, 8);
    EXPECT_NEAR(sum, 1.0f, 1e-6f) << d;
  }
}

}  // namespace penumbra::test
