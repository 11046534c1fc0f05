// The converged reference's shaded image against an independent quadrature of the direct
// illumination of a rect light on a floor (no occluder), on metal and dielectric floors across
// roughness (tests/floor_quadrature.h: the BRDF written out again, not taken from
// shading/shaders/shading.h, and a deterministic Gauss-Legendre rule), so the MIS estimator
// (shading/light_integral.h), its pdfs and its light-intersection code are checked against
// nothing they share.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "floor_quadrature.h"
#include "shared/shared.h"  // NOLINT: shared with GLSL
#include "reference/embree_reference.h"

namespace penumbra {
namespace {

using namespace test::quadrature;

Scene floorScene(const FloorSetup& s) {
  Scene scene;
  scene.materials.push_back(Material{});
  SceneMesh floor;
  floor.name = "floor";
  floor.mesh.positions = {{-20, 0, -20}, {20, 0, -20}, {20, 0, 20}, {-20, 0, 20}};
  floor.mesh.triangles = {{0u, 2u, 1u}, {0u, 3u, 2u}};
  scene.meshes.push_back(floor);
  Light l;
  l.name = "rect";
  l.position = glm::vec3(s.lightCentre);
  l.normal = {0.0f, -1.0f, 0.0f};
  l.tangent = {1.0f, 0.0f, 0.0f};  // bitangent = normal x tangent = +z
  l.size = {float(2.0 * s.halfW), float(2.0 * s.halfH)};
  scene.lights.push_back(l);
  return scene;
}

// A grid of floor points around the highlight (the eye's mirror image of the light lands near
// z = 1.4) and the light's diffuse pool.
CpuGBuffer floorGBuffer(const FloorSetup& s, const Brdf& m, int n) {
  CpuGBuffer g;
  g.width = g.height = n;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      g.position.push_back({float(-1.2 + 2.4 * (x + 0.5) / n), 0.0f, float(-0.4 + 2.6 * (y + 0.5) / n)});
      g.normal.push_back({0.0f, 1.0f, 0.0f});
      g.shadingNormal.push_back({0.0f, 1.0f, 0.0f});
      g.valid.push_back(1);
      g.baseColor.push_back(glm::vec3(float(m.baseColor)));
      g.material.push_back({float(m.metallic), float(m.roughness), float(PENUMBRA_BRDF_METALLIC_ROUGHNESS)});
    }
  g.camera = glm::vec3(s.eye);
  return g;
}

struct Case {
  const char* name;
  Brdf brdf;
};

// The relative RMSE of the converged reference's red channel: its RMSE over the exact image's RMS
// (the relative L2 error, which a per-pixel relative standard error bounds).
// Also its own stated noise on the same scale (the root of the summed variances over the RMS).
double relativeRmse(const Case& c, int n, const shading::IntegratorOptions& o, double* meanSamples = nullptr,
                    double* noise = nullptr) {
  const FloorSetup s;
  const Scene scene = floorScene(s);
  const CpuGBuffer g = floorGBuffer(s, c.brdf, n);
  const EmbreeReference rt(scene);
  const VisibilityResult r = rt.converged(g, scene.lights[0], scene, o);
  const GaussRule rule(8);
  double se = 0.0, sum = 0.0, stated = 0.0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const double want = exactRadiance(s, c.brdf, glm::dvec3(g.position[std::size_t(y) * n + x]), rule);
      const double got = r.radiance.at(x, y, 0);
      se += (got - want) * (got - want), sum += want * want;
      stated += r.radianceVariance.at(x, y, 0);
    }
  if (meanSamples) *meanSamples = r.meanSamples;
  if (noise) *noise = std::sqrt(stated / sum);
  return std::sqrt(se / sum);
}

std::vector<Case> cases() {
  std::vector<Case> out;
  for (double r : {0.05, 0.1, 0.3, 0.5, 1.0}) {
    out.push_back({"metal", {1.0, 1.0, r}});
    out.push_back({"dielectric", {0.8, 0.0, r}});
  }
  return out;
}

// The quadrature states its own error: orders 6 and 8 on every cell agree to 1e-6 relative on
// each case's pixels (a coarse grid of them), far below the 2e-3 the reference is held to.
TEST(ConvergedReference, QuadratureAgreesWithItselfAtTwoOrders) {
  const FloorSetup s;
  const GaussRule six(6), eight(8);
  double worst = 0.0;
  for (const Case& c : cases()) {
    const CpuGBuffer g = floorGBuffer(s, c.brdf, 8);
    for (const glm::vec3& p : g.position) {
      const double a = exactRadiance(s, c.brdf, glm::dvec3(p), six), b = exactRadiance(s, c.brdf, glm::dvec3(p), eight);
      worst = std::max(worst, std::abs(a - b) / std::max(b, 1e-3));
    }
  }
  std::printf("quadrature, orders 6 and 8: largest relative difference %.2e\n", worst);
  EXPECT_LE(worst, 1e-6);
}

TEST(ConvergedReference, QuadratureOfTheRectLightOnGlossyFloors) {
  for (const Case& c : cases()) {
    double samples = 0.0, noise = 0.0;
    const double e = relativeRmse(c, 16, {}, &samples, &noise);
    std::printf(
        "%-10s roughness %.2f: relative RMSE %.2e against the quadrature (its own noise %.2e), %.0f light "
        "samples a pixel\n",
        c.name, c.brdf.roughness, e, noise, samples);
    EXPECT_LE(e, 2e-3) << c.name << " roughness " << c.brdf.roughness;
    // The noise it states is its error's size, not a flattering bound.
    EXPECT_GT(noise, e / 3) << c.name << " roughness " << c.brdf.roughness;
    EXPECT_LT(noise, e * 3) << c.name << " roughness " << c.brdf.roughness;
  }
}

// Light samples alone (the reference before MIS: 1024 a pixel) miss the goal on narrow lobes, and
// four times as many do not help much: MIS, not the count, is what converges there.
TEST(ConvergedReference, LightSamplesAloneDoNotConvergeOnNarrowLobes) {
  for (int count : {1024, 4096}) {
    shading::IntegratorOptions o;
    o.brdfSampling = false;
    o.target = 0.0;
    o.maxSamples = o.minSamples = count;
    for (double roughness : {0.05, 0.1}) {
      const double e = relativeRmse({"metal", {1.0, 1.0, roughness}}, 24, o);
      std::printf("light samples only, %d a pixel, metal roughness %.2f: relative RMSE %.2e\n", count, roughness, e);
      EXPECT_GT(e, 1e-2);
    }
  }
}

}  // namespace
}  // namespace penumbra
