// An independent quadrature of a rect light's direct illumination on a floor (no occluder): the
// BRDF (glTF 2.0 Appendix B: GGX, separable Smith, Schlick) written out again, not taken from
// shading/shaders/shading.h, and a deterministic Gauss-Legendre product rule on a grid graded around the
// mirror point. The truth the converged reference (raytrace_converged_test.cpp) and the LTC
// table's unshadowed term (shading_ltc_test.cpp) are held to. Test-only; header so that each
// test executable compiles its own copy without a library between them.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <glm/glm.hpp>

namespace penumbra::test::quadrature {

inline constexpr double kPi = std::numbers::pi;

struct Brdf {
  double baseColor = 1.0, metallic = 1.0, roughness = 0.5;
  double alpha() const {
    const double r = std::max(roughness, 0.045);  // the renderer's documented clamp
    return r * r;
  }
  double f0() const { return 0.04 * (1.0 - metallic) + baseColor * metallic; }
  double fresnel(double vh) const { return f0() + (1.0 - f0()) * std::pow(1.0 - std::max(vh, 0.0), 5.0); }
  // Smith G1 for GGX.
  static double g1(double c, double a2) { return 2.0 * c / (c + std::sqrt(a2 + (1.0 - a2) * c * c)); }
  // The specular part times cos(theta_l): F D G / (4 |n.v|), n = z.
  double specularCos(const glm::dvec3& v, const glm::dvec3& l) const {
    if (!(l.z > 0.0)) return 0.0;
    const glm::dvec3 h = glm::normalize(v + l);
    if (!(h.z > 0.0)) return 0.0;
    const double a2 = alpha() * alpha();
    const double d = a2 / (kPi * std::pow(h.z * h.z * (a2 - 1.0) + 1.0, 2.0));
    const double nv = std::max(v.z, 1e-4);
    return fresnel(glm::dot(v, h)) * d * g1(l.z, a2) * g1(nv, a2) / (4.0 * nv);
  }
  // The diffuse part times cos(theta_l).
  double diffuseCos(const glm::dvec3& v, const glm::dvec3& l) const {
    if (!(l.z > 0.0)) return 0.0;
    return (1.0 - fresnel(glm::dot(v, glm::normalize(v + l)))) * baseColor * (1.0 - metallic) / kPi * l.z;
  }
};

// ---- the scene: a floor (y = 0, normal +y) under a 1 x 0.6 rect light facing down ----------

struct FloorSetup {
  glm::dvec3 lightCentre{0.0, 1.0, 0.0};
  double halfW = 0.5, halfH = 0.3;  // along x and z
  glm::dvec3 eye{0.0, 1.5, 3.5};
};

// Local frame of the floor: z = +y (normal), x = +x, y = -z (right-handed).
inline glm::dvec3 toLocal(const glm::dvec3& w) { return {w.x, -w.z, w.y}; }
inline glm::dvec3 toWorld(const glm::dvec3& l) { return {l.x, l.z, -l.y}; }

// Gauss-Legendre nodes and weights of order n on [0, 1] (Newton's iteration on P_n, Numerical
// Recipes 4.6).
struct GaussRule {
  std::vector<double> x, w;
  explicit GaussRule(int n) {
    for (int i = 0; i < n; ++i) {
      double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 0.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = 0.0;
        for (int j = 0; j < n; ++j) {
          const double p2 = p1;
          p1 = p0;
          p0 = ((2.0 * j + 1.0) * z * p1 - j * p2) / (j + 1.0);
        }
        dp = n * (z * p0 - p1) / (z * z - 1.0);
        const double dz = p0 / dp;
        z -= dz;
        if (std::abs(dz) < 1e-15) break;
      }
      x.push_back(0.5 * (1.0 - z));
      w.push_back(1.0 / ((1.0 - z * z) * dp * dp));
    }
  }
};

// Cuts of [lo, hi] at centre +- w0 2^i: intervals that grow geometrically away from `centre`
// (the lobe's peak), so that a fixed rule per interval resolves a lobe of width ~w0 anywhere.
inline std::vector<double> gradedCuts(double lo, double hi, double centre, double w0) {
  std::vector<double> c = {lo, hi};
  if (centre > lo && centre < hi) c.push_back(centre);
  for (double w = w0; centre - w > lo || centre + w < hi; w *= 2.0)
    for (double x : {centre - w, centre + w})
      if (x > lo && x < hi) c.push_back(x);
  std::sort(c.begin(), c.end());
  return c;
}

// The exact radiance towards the eye from floor point p (L = 1): over the light's area, the
// product rule of `rule` on each cell of a grid graded around where the mirror direction meets
// the light's plane (the integrand is smooth on the light; only its peak is narrow).
// Which of the BRDF's terms exactRadiance integrates.
enum class Terms { Both, Specular };

inline double exactRadiance(const FloorSetup& s, const Brdf& m, const glm::dvec3& p, const GaussRule& rule,
                            Terms terms = Terms::Both) {
  const glm::dvec3 vw = glm::normalize(s.eye - p), v = toLocal(vw);
  const glm::dvec3 mirror(-vw.x, vw.y, -vw.z);
  const double t = (s.lightCentre.y - p.y) / mirror.y;
  const glm::dvec3 peak = p + t * mirror - s.lightCentre;
  const double w0 = std::max(0.25 * t * m.alpha(), 1e-5);
  const std::vector<double> ca = gradedCuts(-s.halfW, s.halfW, peak.x, w0);
  const std::vector<double> cb = gradedCuts(-s.halfH, s.halfH, peak.z, w0);
  const int n = int(rule.x.size());
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < ca.size(); ++i)
    for (std::size_t j = 0; j + 1 < cb.size(); ++j)
      for (int k = 0; k < n; ++k)
        for (int q = 0; q < n; ++q) {
          const double a = ca[i] + rule.x[k] * (ca[i + 1] - ca[i]), b = cb[j] + rule.x[q] * (cb[j + 1] - cb[j]);
          const glm::dvec3 d = s.lightCentre + glm::dvec3(a, 0.0, b) - p;
          const double r2 = glm::dot(d, d);
          const glm::dvec3 w = d / std::sqrt(r2);
          const glm::dvec3 l = toLocal(w);
          // f cos(theta_s) cos(theta_l) / r^2; cos(theta_l) = w.y for a light facing down.
          const double f = m.specularCos(v, l) + (terms == Terms::Both ? m.diffuseCos(v, l) : 0.0);
          sum += rule.w[k] * rule.w[q] * (ca[i + 1] - ca[i]) * (cb[j + 1] - cb[j]) * f * w.y / r2;
        }
  return sum;
}

}  // namespace penumbra::test::quadrature
