#include "shading/light_integral.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "sampling/light_samples.h"
#include "sampling/rng.h"
#include "shading/shading_shared.hpp"
#include "shading/brdf_sampling.h"

namespace penumbra::shading {
namespace {

constexpr double kPi = std::numbers::pi;

double largest(const glm::dvec3& v) { return std::max({v.x, v.y, v.z}); }

// Welford's running mean and sum of squared deviations, per channel.
struct Running {
  int n = 0;
  glm::dvec3 mean{0.0}, m2{0.0};
  void add(const glm::dvec3& x) {
    ++n;
    const glm::dvec3 d = x - mean;
    mean += d / double(n);
    m2 += d * (x - mean);
  }
  glm::dvec3 varianceOfMean() const { return n > 1 ? m2 / (double(n - 1) * n) : glm::dvec3(0.0); }
};

// The entry and exit distances of the ray p + t w (unit w) through the ball (c, r), the entry
// clamped at 0; false when it misses. The quadratic in the form that keeps the far root exact
// (Numerical Recipes 5.6) and the near one from the product of the roots.
bool chord(const glm::dvec3& p, const glm::dvec3& w, const glm::dvec3& c, double r, double& t0, double& t1) {
  const glm::dvec3 o = p - c;
  const double b = glm::dot(w, o), cc = glm::dot(o, o) - r * r;
  const double disc = b * b - cc;
  if (!(disc > 0.0)) return false;
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  double a0 = q, a1 = q != 0.0 ? cc / q : 0.0;
  if (a0 > a1) std::swap(a0, a1);
  if (!(a1 > 0.0)) return false;
  t0 = std::max(a0, 0.0), t1 = a1;
  return t1 > t0;
}

}  // namespace

LightIntegrator::LightIntegrator(const Scene& scene, const Light& light, float time, const IntegratorOptions& o)
    : scene_(scene), light_(light), time_(time), o_(o) {
  if (o.batch < 1 || o.batch > 65536)
    throw Error("reference-batch", "must be 1..65536, got " + std::to_string(o.batch));
  if (o.minSamples < 1 || o.maxSamples < o.minSamples)
    throw Error("reference-samples", "need 1 <= minimum <= maximum, got " + std::to_string(o.minSamples) + " and " +
                                         std::to_string(o.maxSamples));
  if (!(o.target >= 0.0) || !std::isfinite(o.target))
    throw Error("reference-target", "must be a finite number >= 0, got " + std::to_string(o.target));
  makeLightSampleSet(scene, light, SampleStrategy::Stratified, 1, 1, time);  // validates the light
  texture_ = lightEmissionTexture(scene, light, time);
  c_ = glm::dvec3(light.position);
  n_ = glm::normalize(glm::dvec3(light.normal));
  t_ = glm::normalize(glm::dvec3(light.tangent));
  b_ = glm::cross(n_, t_);
  radius_ = double(light.size.x);
  // Colour * intensity (unless left to the caller), per unit of the light's measure: a ball's
  // radiance along a chord is 3 L / (4 R) times the chord.
  scale_ = (o.lightColour ? glm::dvec3(light.color) * double(light.intensity) : glm::dvec3(1.0)) *
           (light.shape == LightShape::Sphere ? 3.0 / (4.0 * radius_) : 1.0);
  switch (light.shape) {
    case LightShape::Rect:
      density_ = 1.0 / (double(light.size.x) * light.size.y);
      break;
    case LightShape::Disk:
      density_ = 1.0 / (kPi * radius_ * radius_);
      break;
    case LightShape::Sphere:
      density_ = 3.0 / (4.0 * kPi * radius_ * radius_ * radius_);
      break;
    case LightShape::Point:
      density_ = 1.0;
      break;
  }
}

// The BRDF strategy's density in the light's measure per unit solid-angle density, at light
// point x seen from p: cos(theta_l) / r^2 on a one-sided emitter, 1 / (chord r^2) in a ball.
double LightIntegrator::brdfToMeasure(const glm::dvec3& p, const glm::dvec3& x) const {
  const glm::dvec3 d = x - p;
  const double r2 = glm::dot(d, d);
  if (!(r2 > 0.0)) return 0.0;
  const glm::dvec3 w = d / std::sqrt(r2);
  if (light_.shape == LightShape::Sphere) {
    double t0 = 0.0, t1 = 0.0;
    return chord(p, w, c_, radius_, t0, t1) ? 1.0 / ((t1 - t0) * r2) : 0.0;
  }
  return std::max(-glm::dot(n_, w), 0.0) / r2;
}

bool LightIntegrator::hitLight(const glm::dvec3& p, const glm::dvec3& w, double u, Hit& hit) const {
  if (light_.shape == LightShape::Sphere) {
    double t0 = 0.0, t1 = 0.0;
    if (!chord(p, w, c_, radius_, t0, t1)) return false;
    const double t = t0 + u * (t1 - t0);
    hit.x = p + t * w;
    hit.density = 1.0 / ((t1 - t0) * t * t);
    return t > 0.0;
  }
  const double facing = -glm::dot(w, n_);  // one-sided: only the front emits
  if (!(facing > 0.0)) return false;
  const double t = glm::dot(p - c_, n_) / facing;
  if (!(t > 0.0)) return false;
  hit.x = p + t * w;
  const glm::dvec3 q = hit.x - c_;
  const double a = glm::dot(q, t_), b = glm::dot(q, b_);
  const bool inside = light_.shape == LightShape::Rect
                          ? std::abs(a) <= 0.5 * light_.size.x && std::abs(b) <= 0.5 * light_.size.y
                          : a * a + b * b <= radius_ * radius_;
  hit.density = facing / (t * t);
  return inside;
}

// Emission at a light point in the light's measure: colour * intensity * the texture at the
// point's uv (light_samples.cpp appendSample's map, inverted), times 3 / (4 R) in a ball.
glm::dvec3 LightIntegrator::emission(const glm::dvec3& x) const {
  const glm::dvec3 q = x - c_;
  glm::dvec2 uv(0.5);
  switch (light_.shape) {
    case LightShape::Rect:
      uv = {glm::dot(q, t_) / light_.size.x + 0.5, glm::dot(q, b_) / light_.size.y + 0.5};
      break;
    case LightShape::Disk:
      uv = 0.5 + 0.5 * glm::dvec2(glm::dot(q, t_), glm::dot(q, b_)) / radius_;
      break;
    case LightShape::Sphere: {
      const double len = glm::length(q);
      const glm::dvec3 d = len > 0.0 ? q / len : n_;
      const double u = std::atan2(glm::dot(d, b_), glm::dot(d, t_)) / (2.0 * kPi);
      uv = {u - std::floor(u), std::acos(std::clamp(glm::dot(d, n_), -1.0, 1.0)) / kPi};
      break;
    }
    case LightShape::Point:
      break;
  }
  return texture_ ? scale_ * glm::dvec3(emissionAt(*texture_, uv)) : scale_;
}

PixelEstimate LightIntegrator::estimate(const SurfacePoint& s, std::uint32_t seed, const SegmentTracer& trace) const {
  const bool area = light_.isArea();
  const int batch = area ? o_.batch : 1;
  const bool brdf = area && s.shaded && o_.brdfSampling;
  const int minBatches = area ? std::max(2, (o_.minSamples + batch - 1) / batch) : 1;
  const int maxBatches = area ? std::max(minBatches, o_.maxSamples / batch) : 1;

  const glm::dvec3 p(s.p), ng(s.ng);
  const glm::dvec3 v = glm::normalize(glm::dvec3(s.eye) - p);
  const Frame frame = Frame::around(glm::normalize(glm::dvec3(s.shaded ? s.ns : s.ng)));
  const glm::dvec3 vLocal = frame.toLocal(v);
  const double alpha = double(shared::penumbraAlpha(s.roughness));
  // The lobe choice: none but the diffuse for Lambert, only GGX for a metal, else even (either
  // can dominate: a dielectric's 4% specular peak outshines its diffuse at low roughness).
  const bool metal = s.model == PENUMBRA_BRDF_METALLIC_ROUGHNESS &&
                     largest(glm::dvec3(s.baseColor) * double(1.0f - s.metallic)) <= 0.0;
  const double pSpec = s.model != PENUMBRA_BRDF_METALLIC_ROUGHNESS ? 0.0 : metal ? 1.0 : 0.5;
  auto brdfPdf = [&](const glm::dvec3& lLocal) {
    double pdf = 0.0;
    if (pSpec > 0.0) pdf += pSpec * ggxReflectionPdf(vLocal, lLocal, alpha);
    if (pSpec < 1.0) pdf += (1.0 - pSpec) * cosinePdf(lLocal);
    return pdf;
  };
  // f cos(theta_s) [cos(theta_l)] / r^2 towards light point x (0 below either horizon).
  const bool oneSided = light_.shape == LightShape::Rect || light_.shape == LightShape::Disk;
  auto geometry = [&](const glm::dvec3& x, glm::dvec3& l, double& r2) -> glm::dvec3 {
    const glm::dvec3 d = x - p;
    r2 = glm::dot(d, d);
    l = d / std::sqrt(r2);
    const double cosS = std::max(glm::dot(glm::dvec3(s.ns), l), 0.0);
    const double cosL = oneSided ? std::max(-glm::dot(n_, l), 0.0) : 1.0;
    const glm::vec3 f =
        shared::penumbraBrdf(s.ns, glm::vec3(v), glm::vec3(l), s.baseColor, s.metallic, s.roughness, s.model);
    return glm::dvec3(f) * (cosS * cosL / r2);
  };

  PixelEstimate out;
  Running vis, rad;
  std::vector<glm::vec3> targets;
  std::vector<glm::dvec3> visWeight, radWeight;  // per target: what its transmittance scales
  std::vector<float> tr;
  for (int b = 0; b < maxBatches; ++b) {
    const std::uint32_t batchSeed = shared::penumbraHash(seed ^ shared::penumbraHash(std::uint32_t(b) * 2u + 1u));
    const LightSampleSet set = makeLightSampleSet(scene_, light_, SampleStrategy::Stratified, batch, batchSeed, time_);
    targets.clear(), visWeight.clear(), radWeight.clear();
    for (int k = 0; k < set.count; ++k) {
      const glm::dvec3 x(set.positions[k]);
      if (!(glm::dot(ng, x - p) > 0.0)) continue;  // below the horizon: 0, no ray
      glm::dvec3 rw(0.0);
      if (s.shaded) {
        glm::dvec3 l;
        double r2 = 0.0;
        const glm::dvec3 g = geometry(x, l, r2) * scale_ * glm::dvec3(set.luminance[k]);
        double w = 1.0;
        if (brdf) {
          const double pb = brdfPdf(frame.toLocal(l)) * brdfToMeasure(p, x);
          w = density_ * density_ / (density_ * density_ + pb * pb);
        }
        rw = g * (w / density_);
      }
      targets.push_back(set.positions[k]);
      visWeight.push_back(glm::dvec3(set.luminance[k]));
      radWeight.push_back(rw);
    }
    if (brdf) {
      Rng rng((std::uint64_t(batchSeed) << 32) | 0x5bd1e995u);
      for (const glm::vec2& u : unitSquareSamples(SampleStrategy::Stratified, batch, batchSeed ^ 0xa511e9b3u)) {
        const bool specular = rng.uniform() < pSpec;
        const double chordU = rng.uniform();
        const glm::dvec3 lLocal = specular ? sampleGgxReflection(vLocal, alpha, u.x, u.y) : sampleCosine(u.x, u.y);
        const glm::dvec3 l = frame.toWorld(lLocal);
        if (!(lLocal.z > 0.0) || !(glm::dot(ng, l) > 0.0)) continue;
        const double pdf = brdfPdf(lLocal);
        Hit hit;
        if (!(pdf > 0.0) || !hitLight(p, l, chordU, hit)) continue;
        const double pb = pdf * hit.density;
        if (!(pb > 0.0) || !std::isfinite(pb)) continue;
        glm::dvec3 lx;
        double r2 = 0.0;
        const glm::dvec3 g = geometry(hit.x, lx, r2) * emission(hit.x);
        const double w = pb * pb / (pb * pb + density_ * density_);
        targets.push_back(glm::vec3(hit.x));
        visWeight.push_back(glm::dvec3(0.0));
        radWeight.push_back(g * (w / pb));
      }
    }
    tr.assign(targets.size(), 0.0f);
    if (!targets.empty()) trace(s.origin, targets.data(), int(targets.size()), tr.data());
    out.rays += targets.size();
    glm::dvec3 vb(0.0), rb(0.0);
    for (std::size_t j = 0; j < targets.size(); ++j) {
      vb += visWeight[j] * double(tr[j]);
      rb += radWeight[j] * double(tr[j]);
    }
    vis.add(vb / double(set.count));
    rad.add(rb / double(set.count));
    out.samples += set.count;
    // Checked at minBatches 2^k batches only: each check sees twice the data of the last, and few
    // checks keep a run of lucky batches (a spread that underestimates the noise) from stopping
    // a pixel early.
    const int done = b + 1;
    const bool check = done % minBatches == 0 && std::has_single_bit(unsigned(done / minBatches));
    if (check && (!s.shaded || largest(glm::sqrt(rad.varianceOfMean())) <= o_.target * largest(rad.mean))) break;
    if (done == maxBatches) out.capped = s.shaded;
  }
  out.visibility = vis.mean, out.visibilityVariance = vis.varianceOfMean();
  out.radiance = rad.mean, out.radianceVariance = rad.varianceOfMean();
  return out;
}

Image unshadowedIntegral(const CpuGBuffer& g, const Scene& scene, const Light& light, float time,
                         const IntegratorOptions& options) {
  const std::size_t n = std::size_t(g.width) * g.height;
  PENUMBRA_CHECK(g.position.size() == n && g.normal.size() == n && g.valid.size() == n && g.shadingNormal.size() == n &&
                     g.baseColor.size() == n && g.material.size() == n,
                 "unshadowedIntegral needs a G-buffer with the BRDF inputs");
  const LightIntegrator integrator(scene, light, time, options);
  const SegmentTracer unoccluded = [](const glm::vec3&, const glm::vec3*, int count, float* tr) {
    std::fill(tr, tr + count, 1.0f);
  };
  Image out(g.width, g.height, 3, 0.0f);
  PassProgress progress("exact unshadowed term", g.height);
  parallelRows(
      g.height, 0,
      [&](int y, std::uint64_t&) {
        for (int x = 0; x < g.width; ++x) {
          const std::size_t i = std::size_t(y) * g.width + x;
          if (!g.valid[i]) continue;
          SurfacePoint sp;
          sp.p = g.position[i], sp.ng = g.normal[i], sp.eye = g.camera.value_or(sp.p + sp.ng), sp.origin = sp.p;
          sp.shaded = true, sp.ns = g.shadingNormal[i], sp.baseColor = g.baseColor[i];
          sp.metallic = g.material[i].x, sp.roughness = g.material[i].y, sp.model = int(g.material[i].z + 0.5f);
          // Seeds of their own: not the converged reference's (which seeds by the pixel index), so
          // that comparing the two measures both estimates, not one.
          const std::uint32_t seed = shared::penumbraHash(std::uint32_t(i) ^ 0x6a09e667u);
          const glm::dvec3 r = integrator.estimate(sp, seed, unoccluded).radiance;
          for (int c = 0; c < 3; ++c) out.at(x, y, c) = float(r[c]);
        }
      },
      &progress);
  return out;
}

}  // namespace penumbra::shading
