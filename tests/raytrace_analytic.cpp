// Embree reference against closed forms (hard case 23 of shared/docs/hard-cases.md): a square
// occluder parallel under a parallel square light, and a disc under a disc, over a floor.
// Per sample the oracle is exact geometry: the segment from the (offset) ray origin to the
// sample crosses the occluder plane inside or outside the occluder polygon.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "analytic_oracle.h"
#include "sampling/light_samples.h"
#include "shading/shading_shared.hpp"
#include "reference/embree_reference.h"

using namespace penumbra;

namespace {

constexpr float kOccluderHeight = 1.0f, kLightHeight = 3.0f;

// Regular polygon in the plane y = h centred at (cx, cz): `sides` triangles around the centre.
// sides == 4 with radius r*sqrt(2), rotated 45 degrees, is the axis-aligned square of side 2r.
SceneMesh polygon(const char* name, float cx, float cz, float h, float radius, int sides, float rotation) {
  SceneMesh m;
  m.name = name;
  m.mesh.positions.push_back({cx, h, cz});
  for (int i = 0; i < sides; ++i) {
    const double a = rotation + 2.0 * std::numbers::pi * i / sides;
    m.mesh.positions.push_back({cx + radius * float(std::cos(a)), h, cz + radius * float(std::sin(a))});
  }
  for (int i = 0; i < sides; ++i) m.mesh.triangles.push_back({0u, 1u + unsigned(i), 1u + unsigned((i + 1) % sides)});
  return m;
}

// Floor (y = 0, [-10,10]^2) and a horizontal occluder at kOccluderHeight.
Scene plateScene(bool disc) {
  Scene s;
  s.materials.push_back(Material{});
  s.meshes.push_back(polygon("floor", 0.0f, 0.0f, 0.0f, 10.0f * std::sqrt(2.0f), 4, float(std::numbers::pi / 4)));
  if (disc)
    s.meshes.push_back(polygon("disc", 0.0f, 0.0f, kOccluderHeight, 0.5f, 64, 0.0f));
  else
    s.meshes.push_back(
        polygon("square", 0.0f, 0.0f, kOccluderHeight, 0.5f * std::sqrt(2.0f), 4, float(std::numbers::pi / 4)));
  Light l;
  l.name = "light";
  l.shape = disc ? LightShape::Disk : LightShape::Rect;
  l.position = {0.0f, kLightHeight, 0.0f};
  l.normal = {0.0f, -1.0f, 0.0f};
  l.tangent = {1.0f, 0.0f, 0.0f};
  l.size = disc ? glm::vec2(0.5f, 0.0f) : glm::vec2(1.0f, 1.0f);
  s.lights.push_back(l);
  return s;
}

// Floor points on a w x h grid over [-2, 2]^2 (x to the right, z down the image).
CpuGBuffer floorGBuffer(int w, int h) {
  CpuGBuffer g;
  g.width = w, g.height = h;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      g.position.push_back({-2.0f + 4.0f * (x + 0.5f) / w, 0.0f, -2.0f + 4.0f * (y + 0.5f) / h});
      g.normal.push_back({0.0f, 1.0f, 0.0f});
      g.valid.push_back(1);
    }
  return g;
}

// Signed distance of (x, z) to the occluder outline (negative inside), in the occluder plane.
double occluderDistance(const Scene& s, double x, double z) {
  const SceneMesh& m = s.meshes[1];
  double d = -1e30;  // convex polygon: max over edges of the signed edge distance
  const std::size_t n = m.mesh.positions.size() - 1;
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3 a = m.mesh.positions[1 + i], b = m.mesh.positions[1 + (i + 1) % n];
    const glm::dvec2 e = glm::normalize(glm::dvec2(b.x - a.x, b.z - a.z));
    // Counter-clockwise in (x, z): the outward normal is (e.y, -e.x).
    d = std::max(d, (x - a.x) * e.y - (z - a.z) * e.x);
  }
  return d;
}

struct Oracle {
  float transmittance;
  bool nearEdge;
};

// Exact per-sample visibility: where the segment from o to the sample crosses y = h.
Oracle oracle(const Scene& s, glm::dvec3 o, glm::dvec3 sample) {
  const double t = (kOccluderHeight - o.y) / (sample.y - o.y);
  const glm::dvec3 q = o + t * (sample - o);
  const double d = occluderDistance(s, q.x, q.z);
  return {d < 0.0 ? 0.0f : 1.0f, std::abs(d) < 1e-4};
}

void checkSameSamples(bool disc, SampleStrategy strategy, PixelPattern pattern) {
  const Scene scene = plateScene(disc);
  const EmbreeReference rt(scene, 2);
  const CpuGBuffer g = floorGBuffer(40, 40);
  SamplingParams p;
  p.count = 64;
  p.strategy = strategy;
  p.pattern = pattern;
  p.decorrelatedSets = 8;
  const LightSampleSet samples = makeLightSamples(scene, scene.lights[0], p);
  const VisibilityResult r = rt.sameSamples(g, samples);
  ASSERT_EQ(r.samples, 64);
  ASSERT_EQ(r.perSample.size(), g.position.size() * 64);
  int compared = 0, penumbra = 0;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const std::size_t i = std::size_t(y) * g.width + x;
      // No camera in a CPU G-buffer: the origin is p + n * penumbraSurfaceEpsilon(p) (shared/numerics.h).
      const glm::dvec3 o =
          glm::dvec3(g.position[i]) + glm::dvec3(g.normal[i]) * double(shared::penumbraSurfaceEpsilon(g.position[i]));
      const int set = samples.setForPixel(x, y);
      int visible = 0, excluded = 0;
      for (int k = 0; k < 64; ++k) {
        const Oracle want = oracle(scene, o, glm::dvec3(samples.position(set, k)));
        const float got = r.perSample[i * 64 + k];
        if (want.nearEdge) {
          ++excluded;
          EXPECT_TRUE(got == 0.0f || got == 1.0f);
          visible += got == 1.0f;
          continue;
        }
        ++compared;
        ASSERT_EQ(got, want.transmittance) << "pixel " << x << "," << y << " sample " << k;
        visible += want.transmittance == 1.0f;
      }
      const float v = r.visibility.at(x, y, 0);
      penumbra += v > 0.0f && v < 1.0f;
      // Eq. 1: the fraction of visible samples (exact: a multiple of 1/64).
      EXPECT_EQ(v, float(visible) / 64.0f) << x << "," << y;
      EXPECT_EQ(r.visibility.at(x, y, 1), v);
      EXPECT_EQ(r.visibility.at(x, y, 2), v);
    }
  EXPECT_GT(compared, 40 * 40 * 60);
  EXPECT_GT(penumbra, 100);  // the grid crosses umbra, penumbra and lit floor
}

}  // namespace

TEST(RaytraceAnalytic, SquareUnderSquarePerSampleExact) {
  checkSameSamples(false, SampleStrategy::Stratified, PixelPattern::Correlated);
  checkSameSamples(false, SampleStrategy::Poisson, PixelPattern::Decorrelated);
  checkSameSamples(false, SampleStrategy::Vogel, PixelPattern::Interleaved);
}

TEST(RaytraceAnalytic, DiscUnderDiscPerSampleExact) {
  checkSameSamples(true, SampleStrategy::Stratified, PixelPattern::Decorrelated);
  checkSameSamples(true, SampleStrategy::Vogel, PixelPattern::Correlated);
}

TEST(RaytraceAnalytic, ConvergedMatchesClosedForm) {
  // 1024 stratified samples per pixel along a line through umbra, penumbra and light:
  // the visible fraction of the light area within 0.02 (stratified error ~ N^-3/4 at edges).
  for (bool disc : {false, true}) {
    const Scene scene = plateScene(disc);
    const EmbreeReference rt(scene);
    CpuGBuffer g;
    g.width = 41, g.height = 1;
    for (int i = 0; i < g.width; ++i) {
      g.position.push_back({-2.0f + 0.1f * i, 0.0f, 0.07f});
      g.normal.push_back({0.0f, 1.0f, 0.0f});
      g.valid.push_back(1);
    }
    const VisibilityResult r = rt.converged(g, scene.lights[0], scene, {.minSamples = 1024});
    EXPECT_EQ(r.samples, 1024);
    EXPECT_TRUE(r.perSample.empty());
    // The polygonal disc (64 sides) hides slightly less than the circle: cos(pi/64) area ratio.
    for (int i = 0; i < g.width; ++i) {
      const glm::vec3 p = g.position[i];
      const double want = 1.0 - (disc ? test::discHiddenFraction(p.x, p.z, kOccluderHeight, kLightHeight)
                                      : test::squareHiddenFraction(p.x, p.z, kOccluderHeight, kLightHeight));
      EXPECT_NEAR(r.visibility.at(i, 0, 0), want, 0.02) << (disc ? "disc" : "square") << " x=" << p.x;
    }
  }
}

namespace penumbra::test {
namespace {

// The clipped cosine integral of a cap by brute force: a midpoint rule over the cap in its own
// frame (polar angle from the cap's axis, azimuth), the cosine with the normal clamped at 0.
double capCosineBrute(double cosBeta, double sin2Alpha, int n) {
  const double alpha = std::asin(std::sqrt(sin2Alpha)), sinBeta = std::sqrt(1.0 - cosBeta * cosBeta);
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double t = (i + 0.5) / n * alpha;
    for (int j = 0; j < n; ++j) {
      const double ph = (j + 0.5) / n * 2.0 * std::numbers::pi;
      const double z = std::cos(t) * cosBeta - std::sin(t) * std::cos(ph) * sinBeta;
      sum += std::max(z, 0.0) * std::sin(t);
    }
  }
  return sum * (alpha / n) * (2.0 * std::numbers::pi / n);
}

// penumbraBallIrradiance's integral in double with many shells (the same cap formula, in double).
double ballIrradianceDense(double cosBeta, double d, double R, int n) {
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double t = (i + 0.5) / n * std::numbers::pi, r = d - R * std::cos(t);
    const double ca = (d * d + r * r - R * R) / (2.0 * d * r), s2 = std::max(0.0, 1.0 - ca * ca);
    if (s2 > 0.0) sum += std::sin(t) * double(shared::penumbraCapCosine(float(cosBeta), float(s2)));
  }
  return sum * 3.0 * std::numbers::pi / (4.0 * n);
}

}  // namespace

// Snyder's closed form for a cap crossing the horizon (shading/shaders/shading.h
// penumbraCapCosine) against a 400 x 400 quadrature over the cap, wholly above, crossing and
// wholly below the horizon.
TEST(ClosedForms, CapCosineIsTheClippedIntegral) {
  double worst = 0.0;
  for (double cosBeta : {0.9, 0.3, 0.1, 0.0, -0.1, -0.3, -0.8})
    for (double s2 : {0.05, 0.25, 0.6}) {
      const double got = shared::penumbraCapCosine(float(cosBeta), float(s2)), want = capCosineBrute(cosBeta, s2, 400);
      EXPECT_NEAR(got, want, 2e-5 + 1e-4 * want) << "cos(beta) " << cosBeta << ", sin^2(alpha) " << s2;
      worst = std::max(worst, std::abs(got - want));
    }
  std::printf("cap cosine: worst absolute difference %.3g\n", worst);
}

// The sphere light crossing the horizon: the 32-point shell quadrature in float against 20000
// shells in double; wholly above the horizon it is Newton's pi R^2 cos / d^2. Measured 1.7e-5
// relative at d >= 1.1 R (float rounding; the quadrature alone is 5e-6 in double).
TEST(ClosedForms, BallIrradianceAcrossTheHorizon) {
  const glm::vec3 n(0.0f, 1.0f, 0.0f);
  double worst = 0.0;
  for (float d : {1.1f, 1.5f, 3.0f})
    for (float cosBeta : {0.8f, 0.2f, 0.0f, -0.2f, -0.5f}) {
      const float R = 1.0f;
      const glm::vec3 centre = d * glm::vec3(std::sqrt(1.0f - cosBeta * cosBeta), cosBeta, 0.0f);
      const float got = shared::penumbraBallIrradiance(glm::vec3(0.0f), n, n, centre, R);
      const double want = ballIrradianceDense(cosBeta, d, R, 20000);
      ASSERT_GE(got, 0.0f) << "a closed form where the normals agree";
      if (cosBeta * d > R)
        EXPECT_NEAR(got, std::numbers::pi * R * R * cosBeta / (d * d), 1e-6);
      else
        EXPECT_NEAR(got, want, 3e-5 * want + 1e-7) << "d " << d << ", cos(beta) " << cosBeta;
      if (want > 0.0) worst = std::max(worst, std::abs(got - want) / want);
    }
  std::printf("ball irradiance: worst relative difference %.3g\n", worst);
  // Normals that differ with the ball across the geometric plane, and a point inside: no closed form.
  const glm::vec3 tilted = glm::normalize(glm::vec3(0.3f, 1.0f, 0.0f));
  EXPECT_EQ(shared::penumbraBallIrradiance(glm::vec3(0.0f), n, tilted, glm::vec3(0.0f, 0.5f, 1.0f), 1.0f), -1.0f);
  EXPECT_EQ(shared::penumbraBallIrradiance(glm::vec3(0.0f), n, n, glm::vec3(0.0f, 0.5f, 0.0f), 1.0f), -1.0f);
}

// The disk light's unshadowed term (shading/shaders/shading.h penumbraDiskIrradiance, the equal-area 32-gon):
// against the closed form for a parallel disk (analytic_oracle.h), and for tilted disks that
// cross the receiver's horizon against a polar quadrature over the disk in double. Measured:
// 1.4e-4 at worst, where the horizon cuts a tilted disk (the 32-gon's corners at the cut).
TEST(ClosedForms, DiskIrradianceIsLambertsIntegral) {
  const glm::vec3 up(0.0f, 1.0f, 0.0f), x(1.0f, 0.0f, 0.0f), z(0.0f, 0.0f, 1.0f);
  double worst = 0.0;
  for (float rho : {0.0f, 0.2f, 0.6f, 2.0f})
    for (float h : {0.05f, 0.5f, 1.5f}) {
      const float R = 0.3f;
      const double got = shared::penumbraDiskIrradiance(glm::vec3(0.0f), up, up, glm::vec3(rho, h, 0.0f), x, z, R);
      const double want = std::numbers::pi * parallelDiskFormFactor(rho, h, R);
      EXPECT_NEAR(got, want, 2e-4 * want) << "rho " << rho << ", h " << h;
      worst = std::max(worst, std::abs(got - want) / want);
    }
  for (float tilt : {0.6f, 1.2f}) {
    const glm::dvec3 c(0.4, 0.08, 0.1), t(1.0, 0.0, 0.0), b(0.0, std::sin(tilt), std::cos(tilt));
    const double R = 0.3;
    double want = 0.0;  // the integral over the disk of max(cos_s, 0) cos_l / r^2, above the horizon
    const glm::dvec3 ln = glm::normalize(glm::cross(t, b));
    const int n = 2000;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double r = R * std::sqrt((i + 0.5) / n), ph = 2.0 * std::numbers::pi * (j + 0.5) / n;
        const glm::dvec3 q = c + r * (std::cos(ph) * t + std::sin(ph) * b);
        if (!(q.y > 0.0)) continue;
        const double d2 = glm::dot(q, q);
        want += q.y / std::sqrt(d2) * std::abs(glm::dot(ln, q)) / std::sqrt(d2) / d2;
      }
    want *= std::numbers::pi * R * R / (double(n) * n);
    const double got =
        shared::penumbraDiskIrradiance(glm::vec3(0.0f), up, up, glm::vec3(c), glm::vec3(t), glm::vec3(b), float(R));
    EXPECT_NEAR(got, want, 2e-4 * want) << "tilt " << tilt;
    worst = std::max(worst, std::abs(got - want) / want);
  }
  std::printf("disk irradiance: worst relative difference %.3g\n", worst);
}

namespace {
// An independent oracle for the clipped polygon formula: Sutherland-Hodgman on vertex arrays and
// Lambert's sum with acos, all in double.
double clippedLambert(std::vector<glm::dvec3> a, const glm::dvec3& ng, const glm::dvec3& ns) {
  for (const glm::dvec3& h : {ng, ns}) {
    std::vector<glm::dvec3> b;
    for (std::size_t i = 0; i < a.size(); ++i) {
      const glm::dvec3 u = a[i], v = a[(i + 1) % a.size()];
      const double hu = glm::dot(h, u), hv = glm::dot(h, v);
      if (hu > 0.0) b.push_back(u);
      if ((hu > 0.0) != (hv > 0.0)) b.push_back(u + (v - u) * (hu / (hu - hv)));
    }
    a = b;
  }
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const glm::dvec3 u = glm::normalize(a[i]), v = glm::normalize(a[(i + 1) % a.size()]);
    const glm::dvec3 c = glm::cross(u, v);
    if (glm::length(c) > 0.0) sum += std::atan2(glm::length(c), glm::dot(u, v)) * glm::dot(c, ns) / glm::length(c);
  }
  return 0.5 * std::abs(sum);
}
}  // namespace

// The streamed clipping of shading/shaders/shading.h penumbraLightPolygon (edge by edge, no vertex arrays) against
// the array clipping in double, on 20000 random rects and disks (as the same 32-gon) around
// random points, cut by the geometric and shading planes; a third with the two normals equal
// (every cut point then lies on both planes: a classification that differs between an edge's end
// and the next edge's start lost the closing edge, 2205 of 200000 cases off by up to 366x before
// the fix). Measured: 8.9e-5 relative at worst (2.6e-4 over 200000 such cases; floor 1e-3 of the
// value).
TEST(ClosedForms, StreamedPolygonClippingIsArrayClipping) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> U(-1.0f, 1.0f);
  auto random = [&] { return glm::vec3(U(rng), U(rng), U(rng)); };
  double worst = 0.0;
  int clipped = 0;
  for (int it = 0; it < 20000; ++it) {
    const glm::vec3 p = random() * 2.0f, ng = glm::normalize(random());
    glm::vec3 ns = it % 3 == 0 ? ng : glm::normalize(ng + 0.5f * random());
    if (glm::dot(ns, ng) < 0.0f) ns = -ns;
    const glm::vec3 c = random() * 2.0f, t = glm::normalize(random());
    const glm::vec3 b = glm::normalize(glm::cross(t, random()));
    const glm::vec2 half(0.1f + 0.5f * std::abs(U(rng)), 0.1f + 0.5f * std::abs(U(rng)));
    const bool disk = it % 2 == 1;
    std::vector<glm::dvec3> poly;
    if (disk) {
      const double r = double(half.x) * 1.003222080;
      for (int i = 0; i < 32; ++i) {
        const double a = 2.0 * std::numbers::pi * i / 32.0;
        poly.push_back(glm::dvec3(c - p) + r * (std::cos(a) * glm::dvec3(t) + std::sin(a) * glm::dvec3(b)));
      }
    } else {
      for (glm::dvec2 k : {glm::dvec2(-1, -1), glm::dvec2(1, -1), glm::dvec2(1, 1), glm::dvec2(-1, 1)})
        poly.push_back(glm::dvec3(c - p) + k.x * double(half.x) * glm::dvec3(t) + k.y * double(half.y) * glm::dvec3(b));
    }
    const double want = clippedLambert(poly, glm::dvec3(ng), glm::dvec3(ns));
    const double got = disk ? shared::penumbraDiskIrradiance(p, ng, ns, c, t, b, half.x)
                            : shared::penumbraRectIrradiance(p, ng, ns, c, t, b, half);
    const double rel = std::abs(got - want) / std::max(want, 1e-3);
    clipped +=
        std::any_of(poly.begin(), poly.end(), [&](const glm::dvec3& v) { return glm::dot(v, glm::dvec3(ng)) <= 0.0; });
    worst = std::max(worst, rel);
    ASSERT_LE(rel, 1e-3) << "case " << it << (disk ? " (disk)" : " (rect)") << ": " << got << " against " << want;
  }
  std::printf("%d of 20000 cut by the horizon; worst relative difference %.3g\n", clipped, worst);
  EXPECT_GT(clipped, 2000);
}

}  // namespace penumbra::test
