// Embree reference: semi-opaque transmittance, the shared conventions (horizon, origin offset),
// determinism across thread counts, converged mode, eq. 2 with textured lights.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <algorithm>
#include <numbers>

#include "core/error.h"
#include "sampling/light_samples.h"
#include "shared/shared.hpp"
#include "reference/embree_reference.h"

using namespace penumbra;

// Embree 3.13 keeps one internal allocation (~1 KB, per process, not per device) alive at exit;
// LeakSanitizer would fail the sanitizer build on it. Only read by LSan builds.
extern "C" const char* __lsan_default_suppressions() { return "leak:libembree3.so\n"; }

namespace {

// Axis-aligned quad in the plane y = h over [x0,x1] x [z0,z1], split along its diagonal.
SceneMesh quad(const char* name, float x0, float x1, float z0, float z1, float h, int material) {
  SceneMesh m;
  m.name = name;
  m.material = material;
  m.mesh.positions = {{x0, h, z0}, {x1, h, z0}, {x1, h, z1}, {x0, h, z1}};
  m.mesh.triangles = {{0u, 1u, 2u}, {0u, 2u, 3u}};
  return m;
}

// A fan of `sides` triangles around (0, h, 0): every triangle shares the centre vertex.
SceneMesh fan(float h, float radius, int sides, int material) {
  SceneMesh m;
  m.name = "fan";
  m.material = material;
  m.mesh.positions.push_back({0.0f, h, 0.0f});
  for (int i = 0; i < sides; ++i) {
    const double a = 2.0 * std::numbers::pi * i / sides;
    m.mesh.positions.push_back({radius * float(std::cos(a)), h, radius * float(std::sin(a))});
  }
  for (int i = 0; i < sides; ++i) m.mesh.triangles.push_back({0u, 1u + unsigned(i), 1u + unsigned((i + 1) % sides)});
  return m;
}

Scene baseScene() {
  Scene s;
  s.materials.push_back(Material{});  // [0] opaque
  return s;
}

int addMaterial(Scene& s, float opacity) {
  Material m;
  m.opacity = opacity;
  m.alphaMode = AlphaMode::Blend;
  s.materials.push_back(m);
  return int(s.materials.size()) - 1;
}

Light rectLight(float height, float size) {
  Light l;
  l.name = "light";
  l.position = {0.0f, height, 0.0f};
  l.normal = {0.0f, -1.0f, 0.0f};
  l.tangent = {1.0f, 0.0f, 0.0f};
  l.size = {size, size};
  return l;
}

CpuGBuffer floorGBuffer(int w, int h, float extent) {
  CpuGBuffer g;
  g.width = w, g.height = h;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      g.position.push_back({extent * (2.0f * (x + 0.5f) / w - 1.0f), 0.0f, extent * (2.0f * (y + 0.5f) / h - 1.0f)});
      g.normal.push_back({0.0f, 1.0f, 0.0f});
      g.valid.push_back(1);
    }
  return g;
}

// A cluttered scene: floor, opaque boxes of quads, semi-opaque panes, many small triangles
// (so that the high-quality builder uses spatial splits on the big ones).
Scene clutterScene() {
  Scene s = baseScene();
  const int glass = addMaterial(s, 0.4f), smoke = addMaterial(s, 0.25f);
  s.meshes.push_back(quad("floor", -5, 5, -5, 5, 0.0f, 0));
  s.meshes.push_back(quad("pane", -3, 1, -2, 2, 1.0f, glass));
  s.meshes.push_back(quad("pane2", -1, 3, -3, 1, 1.5f, smoke));
  s.meshes.push_back(quad("roof", 0.5f, 2.5f, 0.5f, 2.5f, 2.0f, 0));
  SceneMesh bits;
  bits.name = "bits";
  for (int i = 0; i < 400; ++i) {
    const float x = -2.0f + 0.2f * (i % 20), z = -2.0f + 0.2f * (i / 20), y = 0.5f + 0.001f * i;
    const unsigned b = unsigned(bits.mesh.positions.size());
    bits.mesh.positions.insert(bits.mesh.positions.end(), {{x, y, z}, {x + 0.05f, y, z}, {x, y + 0.05f, z + 0.05f}});
    bits.mesh.triangles.push_back({b, b + 1, b + 2});
  }
  s.meshes.push_back(bits);
  s.lights.push_back(rectLight(4.0f, 2.0f));
  return s;
}

}  // namespace

TEST(Raytrace, OpaqueSegments) {
  Scene s = baseScene();
  s.meshes.push_back(quad("plate", -1, 1, -1, 1, 1.0f, 0));
  const EmbreeReference rt(s, 1);
  EXPECT_EQ(rt.transmittance({0, 0, 0}, {0, 2, 0}), 0.0f);
  EXPECT_EQ(rt.transmittance({0, 2, 0}, {0, 0, 0}), 0.0f);  // both sides of a surface occlude
  EXPECT_EQ(rt.transmittance({2, 0, 0}, {2, 2, 0}), 1.0f);
  EXPECT_EQ(rt.transmittance({0, 0, 0}, {0, 0.99f, 0}), 1.0f);  // stops before the plate
  // The segment ends just before its end point: a sample lying on a surface is not occluded.
  EXPECT_EQ(rt.transmittance({0, 0, 0}, {0, 1.0f, 0}), 1.0f);
  EXPECT_EQ(rt.raysCast(), 5.0);
}

TEST(Raytrace, SemiOpaquePanesMultiply) {
  Scene s = baseScene();
  const int half = addMaterial(s, 0.5f), third = addMaterial(s, 0.3f);
  s.meshes.push_back(quad("pane 0.5", -1, 1, -1, 1, 1.0f, half));
  s.meshes.push_back(quad("pane 0.3", -1, 1, -1, 1, 2.0f, third));
  const EmbreeReference rt(s, 1);
  EXPECT_NEAR(rt.transmittance({0.3f, 0, 0.2f}, {0.3f, 3, 0.2f}), 0.35f, 1e-6f);
  EXPECT_NEAR(rt.transmittance({0.3f, 3, 0.2f}, {0.3f, 0, 0.2f}), 0.35f, 1e-6f);
  EXPECT_NEAR(rt.transmittance({0.3f, 0, 0.2f}, {0.3f, 1.5f, 0.2f}), 0.5f, 1e-6f);
  EXPECT_NEAR(rt.transmittance({0.3f, 1.5f, 0.2f}, {0.3f, 3, 0.2f}), 0.7f, 1e-6f);
  // Over a grid of slanted rays, always both panes, each once.
  for (int i = 0; i < 21; ++i)
    for (int j = 0; j < 21; ++j) {
      const glm::vec3 a{-0.9f + 0.09f * i, 0.0f, -0.9f + 0.09f * j};
      EXPECT_NEAR(rt.transmittance(a, a + glm::vec3(0.1f, 3.0f, -0.05f)), 0.35f, 1e-6f);
    }
  // An opaque plate behind them stops everything.
  s.meshes.push_back(quad("wall", -1, 1, -1, 1, 2.5f, 0));
  const EmbreeReference opaque(s, 1);
  EXPECT_EQ(opaque.transmittance({0, 0, 0}, {0, 3, 0}), 0.0f);
  EXPECT_NEAR(opaque.transmittance({0, 0, 0}, {0, 2.2f, 0}), 0.35f, 1e-6f);
}

TEST(Raytrace, SamePaneCountedOnce) {
  // Rays through the shared diagonal of a two-triangle pane and through the centre vertex of a
  // fan (8 triangles share it) cross one surface: transmittance 1 - opacity, not its powers.
  Scene s = baseScene();
  const int half = addMaterial(s, 0.5f);
  s.meshes.push_back(quad("pane", -1, 1, -1, 1, 1.0f, half));
  s.meshes.push_back(fan(2.0f, 1.0f, 8, half));
  const EmbreeReference rt(s, 1);
  EXPECT_NEAR(rt.transmittance({0.25f, 0.0f, 0.25f}, {0.25f, 1.5f, 0.25f}), 0.5f, 1e-6f);
  EXPECT_NEAR(rt.transmittance({-1.0f, 0.0f, -1.0f}, {-1.0f, 1.5f, -1.0f}), 0.5f, 1e-6f);
  EXPECT_NEAR(rt.transmittance({0.0f, 1.5f, 0.0f}, {0.0f, 2.5f, 0.0f}), 0.5f, 1e-6f);
  EXPECT_NEAR(rt.transmittance({0.0f, 0.0f, 0.0f}, {0.0f, 3.0f, 0.0f}), 0.25f, 1e-6f);
  // Along the fan's spokes (edges shared by two triangles).
  for (int i = 0; i < 8; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 8;
    const glm::vec3 p{0.5f * float(std::cos(a)), 1.5f, 0.5f * float(std::sin(a))};
    EXPECT_NEAR(rt.transmittance(p, p + glm::vec3(0, 1, 0)), 0.5f, 1e-6f) << "spoke " << i;
  }
  // Large semi-opaque triangles among many small ones (spatial splits reference a triangle
  // from several leaves): every ray still sees each pane once.
  const Scene c = clutterScene();
  const EmbreeReference cr(c, 1);
  for (int i = 0; i < 40; ++i) {
    const glm::vec3 a{-0.9f + 0.047f * i, 1.2f, 0.8f - 0.043f * i};
    EXPECT_NEAR(cr.transmittance(a, a + glm::vec3(0.01f, 0.5f, 0.02f)), 0.75f, 1e-6f) << i;
  }
}

TEST(Raytrace, TransparentMaterialDoesNotOcclude) {
  Scene s = baseScene();
  s.meshes.push_back(quad("ghost", -1, 1, -1, 1, 1.0f, addMaterial(s, 0.0f)));
  s.meshes.push_back(quad("wall", -1, 1, -1, 1, 2.0f, addMaterial(s, 1.0f)));
  const EmbreeReference rt(s, 1);
  EXPECT_EQ(rt.transmittance({0, 0, 0}, {0, 1.5f, 0}), 1.0f);
  EXPECT_EQ(rt.transmittance({0, 0, 0}, {0, 3, 0}), 0.0f);
  s.meshes[0].material = 7;
  EXPECT_THROW(EmbreeReference bad(s, 1), Error);
}

TEST(Raytrace, HorizonRule) {
  // A tilted surface sees part of the light below its horizon: those samples are 0 without a
  // ray; a surface facing away sees nothing.
  Scene s = baseScene();
  const Light light = rectLight(1.0f, 4.0f);
  const EmbreeReference rt(s, 1);
  const LightSampleSet samples = makeLightSamples(s, light, SamplingParams{64});
  CpuGBuffer g;
  g.width = 3, g.height = 1;
  g.position = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  const glm::vec3 tilted = glm::normalize(glm::vec3(1, 1, 0));
  g.normal = {{0, 1, 0}, tilted, {0, -1, 0}};
  g.valid = {1, 1, 1};
  const VisibilityResult r = rt.sameSamples(g, samples);
  EXPECT_EQ(r.visibility.at(0, 0, 0), 1.0f);
  int above = 0;
  for (int k = 0; k < 64; ++k) {
    const bool up = glm::dot(tilted, samples.position(0, k)) > 0.0f;
    above += up;
    EXPECT_EQ(r.perSample[64 + k], up ? 1.0f : 0.0f) << k;
    EXPECT_EQ(r.perSample[128 + k], 0.0f);
  }
  EXPECT_GT(above, 20);
  EXPECT_LT(above, 64);
  EXPECT_EQ(r.visibility.at(1, 0, 0), float(above) / 64.0f);
  EXPECT_EQ(r.visibility.at(2, 0, 0), 0.0f);
  EXPECT_EQ(rt.raysCast(), double(64 + above));  // no rays below the horizon
}

TEST(Raytrace, InvalidPixelsAreZero) {
  Scene s = baseScene();
  const EmbreeReference rt(s, 1);
  CpuGBuffer g = floorGBuffer(2, 2, 1.0f);
  g.valid[3] = 0;
  const VisibilityResult r = rt.sameSamples(g, makeLightSamples(s, rectLight(2.0f, 1.0f), SamplingParams{4}));
  EXPECT_EQ(r.visibility.at(0, 0, 0), 1.0f);
  EXPECT_EQ(r.visibility.at(1, 1, 0), 0.0f);
  EXPECT_EQ(r.perSample[3 * 4], 0.0f);
}

TEST(Raytrace, TexturedLightWeightsSamples) {
  // Eq. 2: V_rgb = 1/N sum L_i T_i. Unoccluded: the mean luminance; the occluded half of the
  // light removes its samples' luminance.
  Scene s = baseScene();
  Texture tex;
  tex.image = Image(2, 1, 4, 1.0f);
  tex.image.at(0, 0, 0) = 0.0f;  // left texel: (0, 1, 1); right: (1, 1, 1)
  s.textures.push_back(tex);
  Light light = rectLight(2.0f, 2.0f);
  light.emissionFrames = {0};
  // A wall over x > 0 shadows the right half of the light (as seen from the origin).
  s.meshes.push_back(quad("half", 0.0f, 3.0f, -3.0f, 3.0f, 1.0f, 0));
  const EmbreeReference rt(s, 1);
  SamplingParams p;
  p.count = 16;
  const LightSampleSet samples = makeLightSamples(s, light, p);
  CpuGBuffer g;
  g.width = 1, g.height = 1;
  g.position = {{0, 0, 0}};
  g.normal = {{0, 1, 0}};
  g.valid = {1};
  const VisibilityResult r = rt.sameSamples(g, samples);
  glm::dvec3 want(0.0);
  for (int k = 0; k < 16; ++k)
    if (samples.position(0, k).x < 0.0f) want += glm::dvec3(samples.luminance[k]);
  want /= 16.0;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.visibility.at(0, 0, c), want[c], 1e-6);
  EXPECT_LT(r.visibility.at(0, 0, 0), r.visibility.at(0, 0, 1));  // red fades to the left
}

TEST(Raytrace, DeterministicAcrossThreadCounts) {
  const Scene s = clutterScene();
  const CpuGBuffer g = floorGBuffer(64, 48, 4.0f);
  SamplingParams p;
  p.count = 32;
  p.pattern = PixelPattern::Decorrelated;
  const LightSampleSet samples = makeLightSamples(s, s.lights[0], p);
  const EmbreeReference one(s, 1), two(s, 2);
  const VisibilityResult a = one.sameSamples(g, samples), b = two.sameSamples(g, samples);
  const VisibilityResult c = two.sameSamples(g, samples);
  ASSERT_EQ(a.perSample.size(), b.perSample.size());
  EXPECT_EQ(std::memcmp(a.perSample.data(), b.perSample.data(), a.perSample.size() * 4), 0);
  EXPECT_EQ(std::memcmp(a.perSample.data(), c.perSample.data(), a.perSample.size() * 4), 0);
  EXPECT_EQ(std::memcmp(a.visibility.data.data(), b.visibility.data.data(), a.visibility.data.size() * 4), 0);
  // The scene does produce fractional transmittance, umbra and light.
  int partial = 0, zero = 0, one_ = 0;
  for (float t : a.perSample) partial += t > 0.0f && t < 1.0f, zero += t == 0.0f, one_ += t == 1.0f;
  EXPECT_GT(partial, 1000);
  EXPECT_GT(zero, 1000);
  EXPECT_GT(one_, 1000);
  const VisibilityResult ca = one.converged(g, s.lights[0], s, {.minSamples = 64});
  const VisibilityResult cb = two.converged(g, s.lights[0], s, {.minSamples = 64});
  EXPECT_EQ(std::memcmp(ca.visibility.data.data(), cb.visibility.data.data(), ca.visibility.data.size() * 4), 0);
}

TEST(Raytrace, StreamsMatchSingleSegments) {
  // sameSamples traces each pixel's rays as one Embree stream (the filter finds its ray by id);
  // every per-sample result equals the same segment traced alone.
  const Scene s = clutterScene();
  const CpuGBuffer g = floorGBuffer(12, 10, 3.0f);
  SamplingParams p;
  p.count = 128;
  p.strategy = SampleStrategy::Poisson;
  p.pattern = PixelPattern::Interleaved;
  const LightSampleSet samples = makeLightSamples(s, s.lights[0], p);
  const EmbreeReference rt(s, 2);
  const VisibilityResult r = rt.sameSamples(g, samples);
  int partial = 0;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const std::size_t i = std::size_t(y) * g.width + x;
      // No camera in a CPU G-buffer: the origin moves along the normal (shared/numerics.h).
      const glm::vec3 o = shared::penumbraShadowOrigin(g.position[i], g.normal[i], g.position[i] + g.normal[i]);
      const int set = samples.setForPixel(x, y);
      for (int k = 0; k < 128; ++k) {
        const float want = rt.transmittance(o, samples.position(set, k));
        ASSERT_EQ(r.perSample[i * 128 + k], want) << x << "," << y << " sample " << k;
        partial += want > 0.0f && want < 1.0f;
      }
    }
  EXPECT_GT(partial, 1000);
}

TEST(Raytrace, ConvergedExtremes) {
  Scene s = baseScene();
  s.meshes.push_back(quad("floor", -10, 10, -10, 10, 0.0f, 0));
  s.meshes.push_back(quad("big", -10, -2, -10, 10, 1.0f, 0));
  const Light light = rectLight(3.0f, 1.0f);
  const EmbreeReference rt(s);
  CpuGBuffer g;
  g.width = 2, g.height = 1;
  g.position = {{6.0f, 0.0f, 0.0f}, {-6.0f, 0.0f, 0.0f}};  // open sky, deep under the plate
  g.normal = {{0, 1, 0}, {0, 1, 0}};
  g.valid = {1, 1};
  const double before = rt.raysCast();
  const VisibilityResult r = rt.converged(g, light, s, {.minSamples = 1024});
  EXPECT_EQ(r.visibility.at(0, 0, 0), 1.0f);
  EXPECT_EQ(r.visibility.at(1, 0, 0), 0.0f);
  EXPECT_EQ(rt.raysCast() - before, 2048.0);
  EXPECT_THROW(rt.converged(g, light, s, {.minSamples = 0}), Error);
}

TEST(Raytrace, SurfaceEpsilonIsRelativeToThePoint) {
  // shared/numerics.h penumbraSurfaceEpsilon: 2^-15 of the largest coordinate (256 ULPs, Waechter and
  // Binder 2019), never below 2^-115; independent of any scene size.
  using shared::penumbraSurfaceEpsilon;
  EXPECT_EQ(penumbraSurfaceEpsilon(glm::vec3(1.0f, -3.0f, 2.0f)), 3.0f / 32768.0f);
  EXPECT_EQ(penumbraSurfaceEpsilon(glm::vec3(0.0f)), std::ldexp(1.0f, -115));  // the floor keeps it positive
  for (const glm::vec3 p :
       {glm::vec3(0.3f, 1.7f, -2.9f), glm::vec3(1e5f, 3.0f, -1e5f), glm::vec3(-7e-2f, 0.0f, 4e-2f)}) {
    const float e = penumbraSurfaceEpsilon(p);
    EXPECT_EQ(penumbraSurfaceEpsilon(-p), e);                     // mirrored
    EXPECT_EQ(penumbraSurfaceEpsilon(1024.0f * p), 1024.0f * e);  // scaled (a power of two: exact)
    // The origin leaves its surface by far more than the float spacing at p, at every magnitude.
    const glm::vec3 n(0.0f, 1.0f, 0.0f);
    const glm::vec3 o = shared::penumbraShadowOrigin(p, n, p + glm::vec3(0.0f, 1.0f, 1.0f));
    const double off = double(o.y) - double(p.y);
    EXPECT_GT(off, 0.9 * double(e)) << p.x;
    const float m = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    EXPECT_GE(double(e), 100.0 * double(std::nextafter(m, 1e30f) - m)) << p.x;  // >= 100 ULPs of p
    EXPECT_LT(off, 1.1 * double(e));
  }
}

TEST(Raytrace, Throughput) {
  // Not a gate: reports occlusion rays/s on a simple scene (floor, panes, 400 small triangles).
  for (bool semiOpaque : {false, true}) {
    Scene s = clutterScene();
    if (!semiOpaque)
      for (Material& m : s.materials) m.opacity = 1.0f;
    const CpuGBuffer g = floorGBuffer(128, 128, 4.0f);
    SamplingParams p;
    p.count = 64;
    p.pattern = PixelPattern::Decorrelated;
    const LightSampleSet samples = makeLightSamples(s, s.lights[0], p);
    const EmbreeReference rt(s);
    const auto t0 = std::chrono::steady_clock::now();
    rt.sameSamples(g, samples);
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("[ rays/s   ] %s: %.0f rays in %.3f s = %.2f M rays/s\n", semiOpaque ? "semi-opaque" : "opaque",
                rt.raysCast(), sec, rt.raysCast() / sec * 1e-6);
    EXPECT_GT(rt.raysCast(), 128.0 * 128 * 60);
  }
}
