// The Hamburger 4MSM reconstruction (common/shadow_map/shaders/moments.h penumbraMsm4, msm and msm-soft) on depth
// distributions whose answer is known, GL-free. The moments are biased and standardised in double
// as src/techniques/msm/shaders/msm_resolve.frag does (boxMoments), then reconstructed in float.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "techniques/common/shadow_map/moments.hpp"

namespace penumbra::test {
namespace {

// A distribution of depths u in [-1, 1]: (depth, weight) pairs, weights summing to 1.
using Distribution = std::vector<std::pair<double, double>>;

struct Result {
  double g, blocker;  // shadow intensity; average blocker depth (u)
};

// msm_resolve.frag boxMoments + momentShadow: raw moments, standardised (the variance at least
// `floor`), biased by common/shadow_map/shaders/moments.h penumbraMsmBias, reconstructed.
Result msm(const Distribution& d, double uf, float alpha, double floor = 0.0) {
  double m[4] = {0, 0, 0, 0};
  for (auto [z, w] : d)
    for (int k = 0; k < 4; ++k) m[k] += w * std::pow(z, k + 1);
  const double mu = m[0], c2 = std::max(m[1] - mu * mu, floor);
  const double c3 = m[2] - 3.0 * mu * m[1] + 2.0 * mu * mu * mu;
  const double c4 = m[3] - 4.0 * mu * m[2] + 6.0 * mu * mu * m[1] - 3.0 * mu * mu * mu * mu;
  const double sd = std::sqrt(c2);
  const glm::vec4 b = shared::penumbraMsmBias(float(c3 / (sd * c2)), float(c4 / (c2 * c2)), alpha);
  const glm::vec2 r = shared::penumbraMsm4(b, float((uf - mu) / sd));
  const double g = r.x, sum = mu * r.x + sd * r.y;
  return {g, g > 0.0 ? sum / g : 0.0};
}

// The paper's way: the raw moments biased towards a fixed vector (here the two-point distribution
// at the ends of [-1, 1], (0, 1, 0, 1)) straight into the float reconstruction.
double msmRaw(const Distribution& d, double uf, double alpha) {
  double m[4] = {0, 0, 0, 0};
  for (auto [z, w] : d)
    for (int k = 0; k < 4; ++k) m[k] += w * std::pow(z, k + 1);
  const double target[4] = {0.0, 1.0, 0.0, 1.0};
  glm::vec4 b;
  for (int k = 0; k < 4; ++k) b[k] = float((1.0 - alpha) * m[k] + alpha * target[k]);
  return shared::penumbraMsm4(b, float(uf)).x;
}

// Chebyshev's one-tailed bound on the lit share (VSM, vssm's eq. 1) as a shadow intensity.
double chebyshevShadow(const Distribution& d, double uf) {
  double m1 = 0, m2 = 0;
  for (auto [z, w] : d) m1 += w * z, m2 += w * z * z;
  if (uf <= m1) return 0.0;
  const double var = std::max(m2 - m1 * m1, 1e-12);
  return 1.0 - var / (var + (uf - m1) * (uf - m1));
}

double truth(const Distribution& d, double uf) {
  double g = 0.0;
  for (auto [z, w] : d) g += z < uf ? w : 0.0;
  return g;
}

}  // namespace

// Two depths (an occluder over a receiver, the commonest penumbra texel box): the reconstruction
// puts its points at the two depths, so the shadow intensity is the occluder's share and the
// average blocker depth the occluder's depth, up to the moment bias: also for two layers 0.02
// apart, whose variance a bias towards a fixed vector would swamp.
TEST(Moments, TwoDepthsAreReconstructedExactly) {
  double worstG = 0.0, worstDepth = 0.0;
  for (double f : {0.05, 0.3, 0.5, 0.9})
    for (auto [z1, z2] : {std::pair{-0.8, 0.6}, std::pair{0.1, 0.12}, std::pair{0.9, 0.95}}) {
      const Distribution d = {{z1, f}, {z2, 1.0 - f}};
      const double uf = z2 - 0.25 * (z2 - z1);  // the receiver just above the far layer
      const Result r = msm(d, uf, 1e-5f);
      worstG = std::max(worstG, std::abs(r.g - f));
      worstDepth = std::max(worstDepth, std::abs(r.blocker - z1) / (z2 - z1));
    }
  std::printf("two depths: shadow intensity within %.3g of the share, blocker depth within %.3g of the gap\n", worstG,
              worstDepth);
  EXPECT_LE(worstG, 1e-4);  // measured 4.4e-6 and 2e-6 (alpha = 1e-5)
  EXPECT_LE(worstDepth, 1e-4);
}

// Three layers (a non-planar filter region: two occluders and the receiver's surface behind
// them): no distribution with a point at the receiver's depth and two others matches them, so the
// 4MSM is an approximation there too, but far nearer than the variance bound of VSM (vssm's
// Chebyshev), whose bleeding lights most of the shadow (measured: truth 0.5, 4MSM 0.33,
// Chebyshev 0.03).
TEST(Moments, ThreeLayersBleedLessThanChebyshev) {
  const Distribution d = {{-0.6, 0.2}, {-0.1, 0.3}, {0.7, 0.5}};
  const double uf = 0.3;
  const double t = truth(d, uf), m = msm(d, uf, 1e-5f).g, c = chebyshevShadow(d, uf);
  std::printf("three layers: truth %.4f, 4MSM %.4f, Chebyshev %.4f\n", t, m, c);
  EXPECT_NEAR(m, t, 0.2);
  EXPECT_GT(std::abs(c - t), 2.5 * std::abs(m - t));
}

// A flat box (one depth): in front of the receiver it shadows fully, behind it not at all; the
// bias keeps B invertible (a single depth's Hankel matrix is singular).
TEST(Moments, OneDepthIsLitOrShadowed) {
  for (double z : {-0.9, 0.0, 0.5, 0.99}) {
    const Distribution d = {{z, 1.0}};
    EXPECT_GE(msm(d, z + 0.01, 1e-5f, 1e-12).g, 0.98) << z;
    EXPECT_LE(msm(d, z - 0.01, 1e-5f, 1e-12).g, 0.02) << z;
    EXPECT_TRUE(std::isfinite(msm(d, z, 1e-5f, 1e-12).g)) << z;
  }
}

// Why boxMoments standardises and biases relative to the box's spread: an occluder 1e-3 in front
// of a receiver whose own texels spread over 1e-3, all near u = 0.9 (a contact shadow). Raw
// moments in float lose the box's variance to rounding (b2 - b1^2 cancels at 0.81) and a bias
// towards a fixed vector swamps it (both give 0); standardised ones keep the occluder's share.
TEST(Moments, StandardisingKeepsNarrowClustersInFloat) {
  Distribution d;
  d.push_back({0.898, 0.3});
  for (int i = 0; i < 8; ++i) d.push_back({0.9 + 1e-3 * i / 7.0, 0.7 / 8.0});
  const double uf = 0.8995;  // between the occluder and the receiver's texels
  const double t = truth(d, uf), standardised = msm(d, uf, 1e-5f).g;
  const double raw = msmRaw(d, uf, 3e-7), rawPaper = msmRaw(d, uf, 6e-5);
  std::printf("narrow cluster: truth %.4f, standardised %.4f, raw float %.4f (alpha 3e-7), %.4f (6e-5)\n", t,
              standardised, raw, rawPaper);
  EXPECT_NEAR(standardised, t, 0.04);  // measured 0.273: the 4MSM's own approximation of a spread cluster
  EXPECT_GT(std::abs(raw - t), 0.05);
  EXPECT_GT(std::abs(rawPaper - t), 0.05);
}

}  // namespace penumbra::test
