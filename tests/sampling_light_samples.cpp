// Light-sample sets: determinism, shapes, stratification quality, set patterns, texture lookup,
// errors (DCS paper section 5 and 7.1).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <set>

#include "cli/options.h"
#include "core/error.h"
#include "sampling/light_samples.h"
#include "sampling/sample_sets.hpp"

using namespace penumbra;
using penumbra::cli::parsePixelPattern;
using penumbra::cli::parseSampleStrategy;

namespace {

Scene emptyScene() {
  Scene s;
  s.materials.push_back(Material{});
  return s;
}

Light makeLight(LightShape shape) {
  Light l;
  l.name = "light[0]";
  l.shape = shape;
  l.position = {0.5f, 4.0f, -1.0f};
  l.normal = {0.0f, -1.0f, 0.0f};
  l.tangent = {1.0f, 0.0f, 0.0f};
  l.size = shape == LightShape::Rect ? glm::vec2(2.0f, 1.0f) : glm::vec2(0.75f, 0.0f);
  return l;
}

const LightShape kAreaShapes[] = {LightShape::Rect, LightShape::Disk, LightShape::Sphere};
const SampleStrategy kStrategies[] = {SampleStrategy::Stratified, SampleStrategy::Poisson, SampleStrategy::Vogel};
const PixelPattern kPatterns[] = {PixelPattern::Correlated, PixelPattern::Decorrelated, PixelPattern::Interleaved};

template <class T>
bool bitEqual(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

// Exact star discrepancy of a 2D point set: the supremum over anchored boxes [0,a) x [0,b) is
// reached at a, b among the point coordinates and 1, counting points open or closed.
double starDiscrepancy(const std::vector<glm::vec2>& p) {
  std::vector<float> xs{1.0f}, ys{1.0f};
  for (auto q : p) {
    xs.push_back(q.x);
    ys.push_back(q.y);
  }
  const double n = double(p.size());
  double d = 0.0;
  for (float a : xs)
    for (float b : ys) {
      int open = 0, closed = 0;
      for (auto q : p) {
        open += q.x < a && q.y < b;
        closed += q.x <= a && q.y <= b;
      }
      const double area = double(a) * b;
      d = std::max({d, area - open / n, closed / n - area});
    }
  return d;
}

double minToroidalDistance(const std::vector<glm::vec2>& p) {
  double d = 1e9;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      double dx = std::abs(p[i].x - p[j].x), dy = std::abs(p[i].y - p[j].y);
      dx = std::min(dx, 1.0 - dx), dy = std::min(dy, 1.0 - dy);
      d = std::min(d, std::sqrt(dx * dx + dy * dy));
    }
  return d;
}

std::vector<glm::vec2> randomSet(int n, std::mt19937& g) {
  std::vector<glm::vec2> p(n);
  for (auto& q : p) q = {float(g() * 0x1.0p-32), float(g() * 0x1.0p-32)};  // no distributions
  return p;
}

}  // namespace

TEST(Sampling, DeterministicAndSeeded) {
  const Scene scene = emptyScene();
  for (LightShape shape : kAreaShapes)
    for (SampleStrategy st : kStrategies)
      for (PixelPattern pat : kPatterns) {
        SamplingParams p;
        p.count = 32;
        p.strategy = st;
        p.pattern = pat;
        p.seed = 7;
        const Light l = makeLight(shape);
        const LightSampleSet a = makeLightSamples(scene, l, p), b = makeLightSamples(scene, l, p);
        EXPECT_TRUE(bitEqual(a.positions, b.positions));
        EXPECT_TRUE(bitEqual(a.uv, b.uv));
        EXPECT_TRUE(bitEqual(a.luminance, b.luminance));
        p.seed = 8;
        const LightSampleSet c = makeLightSamples(scene, l, p);
        EXPECT_FALSE(bitEqual(a.positions, c.positions)) << toString(st) << " " << toString(pat);
      }
  for (SampleStrategy st : kStrategies) {
    EXPECT_TRUE(bitEqual(unitSquareSamples(st, 50, 3), unitSquareSamples(st, 50, 3)));
    EXPECT_FALSE(bitEqual(unitSquareSamples(st, 50, 3), unitSquareSamples(st, 50, 4)));
  }
}

TEST(Sampling, OneSampleIsTheCentre) {
  const Scene scene = emptyScene();
  for (LightShape shape : {LightShape::Point, LightShape::Rect, LightShape::Disk, LightShape::Sphere})
    for (SampleStrategy st : kStrategies)
      for (PixelPattern pat : kPatterns) {
        SamplingParams p;
        p.count = 1;
        p.strategy = st;
        p.pattern = pat;
        const Light l = makeLight(shape);
        const LightSampleSet s = makeLightSamples(scene, l, p);
        ASSERT_EQ(s.count, 1);
        ASSERT_EQ(s.setCount, 1);
        EXPECT_EQ(s.setForPixel(5, 9), 0);
        EXPECT_EQ(s.positions[0], l.position);
        EXPECT_EQ(s.uv[0], glm::vec2(0.5f));
      }
  // A point light has one sample whatever the count.
  SamplingParams p;
  p.count = 64;
  p.pattern = PixelPattern::Decorrelated;
  const LightSampleSet s = makeLightSamples(scene, makeLight(LightShape::Point), p);
  EXPECT_EQ(s.count, 1);
  EXPECT_EQ(s.positions.size(), 1u);
  EXPECT_EQ(s.sampleWeight, 1.0f);
  EXPECT_EQ(s.lightNormal, glm::vec3(0.0f));
}

TEST(Sampling, SamplesLieOnTheLight) {
  const Scene scene = emptyScene();
  for (LightShape shape : kAreaShapes)
    for (SampleStrategy st : kStrategies)
      for (PixelPattern pat : kPatterns)
        for (int n : {2, 7, 16, 128}) {
          SamplingParams p;
          p.count = n;
          p.strategy = st;
          p.pattern = pat;
          p.decorrelatedSets = 8;
          const Light l = makeLight(shape);
          const LightSampleSet s = makeLightSamples(scene, l, p);
          ASSERT_EQ(s.positions.size(), std::size_t(s.setCount) * n);
          for (std::size_t i = 0; i < s.positions.size(); ++i) {
            const glm::vec3 d = s.positions[i] - l.position;
            const float u = glm::dot(d, l.tangent), v = glm::dot(d, l.bitangent()), w = glm::dot(d, l.normal);
            ASSERT_TRUE(s.uv[i].x >= 0.0f && s.uv[i].x < 1.0f && s.uv[i].y >= 0.0f && s.uv[i].y < 1.0f);
            if (shape == LightShape::Rect) {
              ASSERT_LE(std::abs(u), 0.5f * l.size.x + 1e-5f);
              ASSERT_LE(std::abs(v), 0.5f * l.size.y + 1e-5f);
              ASSERT_NEAR(w, 0.0f, 1e-6f);
              // uv is the rect parametrisation of the position.
              ASSERT_NEAR(s.uv[i].x, u / l.size.x + 0.5f, 1e-5f);
              ASSERT_NEAR(s.uv[i].y, v / l.size.y + 0.5f, 1e-5f);
            } else if (shape == LightShape::Disk) {
              ASSERT_LE(std::hypot(u, v), l.size.x * (1.0f + 1e-5f));
              ASSERT_NEAR(w, 0.0f, 1e-6f);
            } else {
              ASSERT_LE(glm::length(d), l.size.x * (1.0f + 1e-5f));
            }
          }
        }
}

TEST(Sampling, StratifiedOnePerStratum) {
  for (int side : {2, 3, 4, 8, 11}) {
    const int n = side * side;
    const auto pts = unitSquareSamples(SampleStrategy::Stratified, n, 5);
    std::vector<int> hits(n, 0);
    for (auto q : pts) ++hits[int(q.y * side) * side + int(q.x * side)];
    for (int h : hits) ASSERT_EQ(h, 1) << "N = " << n;
  }
  // Non-square N: rows of base or base+1 cells, each row as tall as its share of N, so every
  // stratum still has area 1/N. N = 10: 4 rows of 3, 3, 2, 2 cells.
  const auto pts = unitSquareSamples(SampleStrategy::Stratified, 10, 5);
  const int cells[] = {3, 3, 2, 2};
  int before = 0, k = 0;
  for (int row = 0; row < 4; ++row) {
    for (int c = 0; c < cells[row]; ++c, ++k) {
      EXPECT_GE(pts[k].y, before / 10.0f);
      EXPECT_LT(pts[k].y, (before + cells[row]) / 10.0f + 1e-6f);
      EXPECT_GE(pts[k].x, float(c) / cells[row]);
      EXPECT_LT(pts[k].x, float(c + 1) / cells[row]);
    }
    before += cells[row];
  }
}

TEST(Sampling, BetterDistributedThanRandom) {
  std::mt19937 g(12345);
  for (int n : {16, 64, 128}) {
    double randomDisc = 0.0, randomDist = 0.0;
    const int trials = 16;
    for (int t = 0; t < trials; ++t) {
      const auto r = randomSet(n, g);
      randomDisc += starDiscrepancy(r) / trials;
      randomDist += minToroidalDistance(r) / trials;
    }
    const double hex = std::sqrt(2.0 / (std::sqrt(3.0) * n));  // best possible min distance
    for (SampleStrategy st : kStrategies) {
      const auto p = unitSquareSamples(st, n, 1);
      const double disc = starDiscrepancy(p), dist = minToroidalDistance(p);
      EXPECT_LT(disc, 0.75 * randomDisc) << toString(st) << " N=" << n;
      if (st != SampleStrategy::Stratified) {
        EXPECT_GT(dist, 2.0 * randomDist) << toString(st);
      }
      if (st == SampleStrategy::Poisson) {
        EXPECT_GT(dist, 0.6 * hex) << "N=" << n;
      }
    }
  }
}

TEST(Sampling, VogelDiskIsTheGoldenSpiral) {
  // The concentric inverse followed by the concentric map gives the spiral back: radius of
  // sample k is R sqrt((k + 0.5) / N), consecutive angles differ by the golden angle.
  const Scene scene = emptyScene();
  const Light l = makeLight(LightShape::Disk);
  SamplingParams p;
  p.count = 64;
  p.strategy = SampleStrategy::Vogel;
  const LightSampleSet s = makeLightSamples(scene, l, p);
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < p.count; ++k) {
    const glm::vec3 d = s.positions[k] - l.position;
    EXPECT_NEAR(glm::length(d), l.size.x * std::sqrt((k + 0.5) / p.count), 1e-5);
    if (k == 0) continue;
    const glm::vec3 e = s.positions[k - 1] - l.position;
    const double a0 = std::atan2(glm::dot(e, l.bitangent()), glm::dot(e, l.tangent));
    const double a1 = std::atan2(glm::dot(d, l.bitangent()), glm::dot(d, l.tangent));
    const double step = std::remainder(a1 - a0 - golden, 2.0 * std::numbers::pi);
    EXPECT_NEAR(step, 0.0, 1e-3) << k;
  }
}

TEST(Sampling, SphereSamplesFillTheBallUniformly) {
  // Radial coordinate stratified in volume: exactly N/8 samples lie within R/2 (1/8 of the
  // volume), and the mean direction is near 0.
  const Scene scene = emptyScene();
  const Light l = makeLight(LightShape::Sphere);
  SamplingParams p;
  p.count = 128;
  const LightSampleSet s = makeLightSamples(scene, l, p);
  int inner = 0;
  glm::dvec3 mean(0.0);
  for (const glm::vec3& q : s.positions) {
    const glm::vec3 d = q - l.position;
    inner += glm::length(d) < 0.5f * l.size.x;
    mean += glm::dvec3(glm::normalize(d));
  }
  EXPECT_NEAR(inner, 16, 1);
  EXPECT_LT(glm::length(mean / 128.0), 0.1);
  EXPECT_FLOAT_EQ(s.sampleWeight, float(std::numbers::pi * 0.75 * 0.75 / 128));
  EXPECT_EQ(s.lightNormal, glm::vec3(0.0f));
}

TEST(Sampling, DecorrelatedSetsAreRotationsOnTheLight) {
  const Scene scene = emptyScene();
  for (LightShape shape : kAreaShapes) {
    SamplingParams p;
    p.count = 16;
    p.pattern = PixelPattern::Decorrelated;
    p.decorrelatedSets = 8;
    const Light l = makeLight(shape);
    const LightSampleSet s = makeLightSamples(scene, l, p);
    ASSERT_EQ(s.setCount, 8);
    const LightSampleSet base = makeLightSamples(scene, l, SamplingParams{16});
    for (int k = 0; k < 16; ++k) EXPECT_EQ(s.position(0, k), base.position(0, k));  // set 0
    for (int j = 1; j < s.setCount; ++j) {
      bool moved = false;
      for (int k = 0; k < 16; ++k) {
        moved |= s.position(j, k) != s.position(0, k);
        if (shape == LightShape::Rect) {
          // Toroidal shift: the same offset (mod 1) for every point of the set.
          const glm::vec2 d0 = s.uv[j * 16] - s.uv[0];
          const glm::vec2 dk = s.uv[j * 16 + k] - s.uv[k];
          EXPECT_NEAR(std::remainder(dk.x - d0.x, 1.0f), 0.0f, 1e-5f);
          EXPECT_NEAR(std::remainder(dk.y - d0.y, 1.0f), 0.0f, 1e-5f);
        } else {
          // Rotation about the light normal through the centre: distance to the centre and
          // height along the normal are kept.
          const glm::vec3 a = s.position(0, k) - l.position, b = s.position(j, k) - l.position;
          EXPECT_NEAR(glm::length(a), glm::length(b), 1e-5f);
          EXPECT_NEAR(glm::dot(a, l.normal), glm::dot(b, l.normal), 1e-5f);
        }
      }
      EXPECT_TRUE(moved) << "set " << j;
    }
  }
}

TEST(Sampling, InterleavedSetsDiffer) {
  const Scene scene = emptyScene();
  for (SampleStrategy st : kStrategies) {
    SamplingParams p;
    p.count = 16;
    p.strategy = st;
    p.pattern = PixelPattern::Interleaved;
    p.interleaveK = 3;
    const LightSampleSet s = makeLightSamples(scene, makeLight(LightShape::Rect), p);
    ASSERT_EQ(s.setCount, 9);
    std::set<std::vector<float>> distinct;
    for (int j = 0; j < 9; ++j) {
      std::vector<float> v;
      for (int k = 0; k < 16; ++k) v.push_back(s.position(j, k).x);
      distinct.insert(v);
    }
    EXPECT_EQ(distinct.size(), 9u) << toString(st);
  }
}

TEST(Sampling, SetForPixel) {
  const Scene scene = emptyScene();
  SamplingParams p;
  p.count = 8;
  p.pattern = PixelPattern::Decorrelated;
  p.decorrelatedSets = 16;
  const LightSampleSet d = makeLightSamples(scene, makeLight(LightShape::Rect), p);
  std::vector<int> hist(16, 0);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) {
      const int set = d.setForPixel(x, y);
      ASSERT_GE(set, 0);
      ASSERT_LT(set, 16);
      ++hist[set];
      // The same function the shaders use (sampling/shaders/sample_sets.h).
      ASSERT_EQ(set, int(penumbra::shared::penumbraSetForPixel(x, y, PENUMBRA_PATTERN_DECORRELATED, 16, 1, p.seed)));
    }
  for (int h : hist) EXPECT_NEAR(h, 4096, 4096 * 0.1);
  // Neighbours rarely share a set.
  int same = 0;
  for (int x = 0; x < 255; ++x) same += d.setForPixel(x, 7) == d.setForPixel(x + 1, 7);
  EXPECT_LT(same, 40);

  p.pattern = PixelPattern::Interleaved;
  p.interleaveK = 4;
  const LightSampleSet il = makeLightSamples(scene, makeLight(LightShape::Rect), p);
  for (int y = 0; y < 9; ++y)
    for (int x = 0; x < 9; ++x) EXPECT_EQ(il.setForPixel(x, y), (y % 4) * 4 + x % 4);
  const LightSampleSet c = makeLightSamples(scene, makeLight(LightShape::Rect), SamplingParams{8});
  EXPECT_EQ(c.setForPixel(13, 17), 0);
}

TEST(Sampling, Radiometry) {
  const Scene scene = emptyScene();
  Light rect = makeLight(LightShape::Rect);
  rect.size = {2.0f, 3.0f};
  const LightSampleSet r = makeLightSamples(scene, rect, SamplingParams{16});
  EXPECT_FLOAT_EQ(r.sampleWeight, 6.0f / 16.0f);
  EXPECT_EQ(r.lightNormal, rect.normal);
  EXPECT_EQ(r.luminance[3], glm::vec3(1.0f));  // untextured
  Light disk = makeLight(LightShape::Disk);
  disk.size.x = 1.0f;
  const LightSampleSet d = makeLightSamples(scene, disk, SamplingParams{16});
  EXPECT_FLOAT_EQ(d.sampleWeight, float(std::numbers::pi / 16.0));
  EXPECT_EQ(d.lightNormal, disk.normal);
}

TEST(Sampling, TextureLuminanceIsBilinear) {
  // 4 x 4 texture: R = column, G = row (row 0 at the top is v = 0), B = 1.
  Scene scene = emptyScene();
  Texture tex;
  tex.source = "ramp";
  tex.image = Image(4, 4, 4, 1.0f);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) tex.image.at(x, y, 0) = float(x), tex.image.at(x, y, 1) = float(y);
  scene.textures.push_back(tex);
  Texture flat;
  flat.image = Image(2, 2, 3, 0.25f);
  scene.textures.push_back(flat);
  for (LightShape shape : kAreaShapes) {
    Light l = makeLight(shape);
    l.emissionFrames = {0};
    SamplingParams p;
    p.count = 64;
    p.pattern = PixelPattern::Decorrelated;
    const LightSampleSet s = makeLightSamples(scene, l, p);
    for (std::size_t i = 0; i < s.uv.size(); ++i) {
      const float r = std::clamp(4.0f * s.uv[i].x - 0.5f, 0.0f, 3.0f);
      const float g = std::clamp(4.0f * s.uv[i].y - 0.5f, 0.0f, 3.0f);
      ASSERT_NEAR(s.luminance[i].r, r, 1e-4f);
      ASSERT_NEAR(s.luminance[i].g, g, 1e-4f);
      ASSERT_NEAR(s.luminance[i].b, 1.0f, 1e-6f);
    }
  }
  // Animated: frame = floor(time * fps) mod frames.
  Light l = makeLight(LightShape::Rect);
  l.emissionFrames = {0, 1};
  l.fps = 2.0f;
  SamplingParams p;
  p.count = 4;
  EXPECT_EQ(makeLightSamples(scene, l, p, 0.6f).luminance[0], glm::vec3(0.25f));
  EXPECT_NE(makeLightSamples(scene, l, p, 1.1f).luminance[0], glm::vec3(0.25f));
}

TEST(Sampling, Errors) {
  const Scene scene = emptyScene();
  for (int n : {0, -1, PENUMBRA_MAX_SAMPLES + 1}) {
    SamplingParams p;
    p.count = n;
    try {
      makeLightSamples(scene, makeLight(LightShape::Rect), p);
      ADD_FAILURE() << "count " << n << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.where(), "samples");
    }
  }
  EXPECT_NO_THROW(makeLightSamples(scene, makeLight(LightShape::Rect), SamplingParams{PENUMBRA_MAX_SAMPLES}));
  const float bad[] = {0.0f, -1.0f, std::nanf(""), INFINITY};
  for (LightShape shape : kAreaShapes)
    for (float v : bad) {
      Light l = makeLight(shape);
      l.size.x = v;
      try {
        makeLightSamples(scene, l, SamplingParams{4});
        ADD_FAILURE() << "size " << v << " accepted";
      } catch (const Error& e) {
        EXPECT_EQ(e.where(), "light[0]");
      }
    }
  Light rect = makeLight(LightShape::Rect);
  rect.size.y = 0.0f;
  EXPECT_THROW(makeLightSamples(scene, rect, SamplingParams{4}), Error);
  Light point = makeLight(LightShape::Point);
  point.size = glm::vec2(0.0f);
  EXPECT_NO_THROW(makeLightSamples(scene, point, SamplingParams{4}));
  Light textured = makeLight(LightShape::Rect);
  textured.emissionFrames = {3};  // no such texture
  EXPECT_THROW(makeLightSamples(scene, textured, SamplingParams{4}), Error);
  SamplingParams sets;
  sets.pattern = PixelPattern::Decorrelated;
  sets.decorrelatedSets = 0;
  EXPECT_THROW(makeLightSamples(scene, makeLight(LightShape::Rect), sets), Error);
  EXPECT_EQ(parseSampleStrategy("poisson"), SampleStrategy::Poisson);
  EXPECT_EQ(parsePixelPattern("interleaved"), PixelPattern::Interleaved);
  EXPECT_THROW(parseSampleStrategy("halton"), Error);
  EXPECT_THROW(parsePixelPattern("random"), Error);
}
