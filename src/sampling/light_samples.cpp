// Light-sample sets (DCS paper section 5 and 7.1): unit-square point sets, their maps onto the
// light shapes, and the per-pixel set patterns (correlated, decorrelated rotations, interleaved).
//
// Everything here is deterministic: one SplitMix64 generator (sampling/rng.h) seeded from the
// parameters, all arithmetic in double rounded once to float.
#include "sampling/light_samples.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "core/error.h"
#include "sampling/rng.h"
#include "sampling/sample_sets.hpp"

namespace penumbra {
namespace {

constexpr double kPi = std::numbers::pi;
// Largest float below 1: unit coordinates are in [0,1) even after rounding to float.
constexpr float kBelowOne = 0x1.fffffep-1f;
// Limits on the number of sets: bounded memory (M * N positions) and bounded dart throwing.
constexpr int kMaxDecorrelatedSets = 4096;
constexpr int kMaxInterleaveK = 16;
// Converged reference sample counts are not limited by the GPU layout, only by memory.
constexpr int kMaxSingleSetCount = 1 << 20;

// Independent streams per (seed, purpose, index): the purposes never share a generator state.
enum Stream : std::uint64_t { kStreamPoints = 1, kStreamRadial = 2, kStreamRotation = 3 };
std::uint64_t streamSeed(std::uint32_t seed, Stream stream, std::uint64_t index = 0) {
  Rng r((std::uint64_t(seed) << 32) ^ (std::uint64_t(stream) << 24) ^ index);
  return r.next();
}

float unitFloat(double x) { return std::min(float(x), kBelowOne); }
double fract(double x) { return x - std::floor(x); }

// ---- unit-square point sets --------------------------------------------------------------

// Jittered grid of nx = floor(sqrt(N)) columns and ceil(N / nx) rows. When N is not a product,
// rows hold base or base+1 cells and a row's height is proportional to its cell count, so every
// stratum has area exactly 1/N (equal weights 1/N in eq. 1 stay unbiased).
std::vector<glm::dvec2> stratified(int n, Rng& rng) {
  int nx = int(std::sqrt(double(n)));
  while ((nx + 1) * (nx + 1) <= n) ++nx;
  while (nx * nx > n) --nx;
  const int rows = (n + nx - 1) / nx;
  const int base = n / rows, extra = n % rows;
  std::vector<glm::dvec2> pts;
  pts.reserve(n);
  int before = 0;  // cells in earlier rows
  for (int row = 0; row < rows; ++row) {
    const int cells = base + (row < extra ? 1 : 0);
    const double y0 = double(before) / n, h = double(cells) / n;
    for (int c = 0; c < cells; ++c) {
      const double jx = rng.uniform(), jy = rng.uniform();
      pts.push_back({(c + jx) / cells, y0 + jy * h});
    }
    before += cells;
  }
  return pts;
}

// Dart throwing with a decreasing radius (Cook 1986 / McCool-Fiume 1992). Distances are
// toroidal so that the Cranley-Patterson shifts of decorrelated rect sets keep the minimum
// distance. The radius starts at the hexagonal-packing distance for N points on the unit torus
// and shrinks by 3% each time 64 consecutive darts fail.
std::vector<glm::dvec2> poisson(int n, Rng& rng) {
  double d = std::sqrt(2.0 / (std::sqrt(3.0) * n));
  std::vector<glm::dvec2> pts;
  pts.reserve(n);
  int failures = 0;
  while (int(pts.size()) < n) {
    const glm::dvec2 c{rng.uniform(), rng.uniform()};
    bool ok = true;
    for (const glm::dvec2& q : pts) {
      double dx = std::abs(c.x - q.x), dy = std::abs(c.y - q.y);
      dx = std::min(dx, 1.0 - dx);
      dy = std::min(dy, 1.0 - dy);
      if (dx * dx + dy * dy < d * d) {
        ok = false;
        break;
      }
    }
    if (ok) {
      pts.push_back(c);
      failures = 0;
    } else if (++failures == 64) {
      d *= 0.97;
      failures = 0;
    }
  }
  return pts;
}

// Shirley-Chiu concentric map, unit square [0,1)^2 -> unit disk (area preserving).
glm::dvec2 squareToDisk(glm::dvec2 u) {
  const double a = 2.0 * u.x - 1.0, b = 2.0 * u.y - 1.0;
  if (a == 0.0 && b == 0.0) return {0.0, 0.0};
  double r, phi;
  if (std::abs(a) > std::abs(b)) {
    r = a;
    phi = kPi / 4.0 * (b / a);
  } else {
    r = b;
    phi = kPi / 2.0 - kPi / 4.0 * (a / b);
  }
  return {r * std::cos(phi), r * std::sin(phi)};
}

// Inverse of squareToDisk: unit disk -> unit square.
glm::dvec2 diskToSquare(glm::dvec2 d) {
  const double r = std::sqrt(d.x * d.x + d.y * d.y);
  double phi = std::atan2(d.y, d.x);
  if (phi < -kPi / 4.0) phi += 2.0 * kPi;  // phi in [-pi/4, 7pi/4)
  double a, b;
  if (phi < kPi / 4.0) {
    a = r;
    b = phi * 4.0 / kPi * r;
  } else if (phi < 3.0 * kPi / 4.0) {
    b = r;
    a = (kPi / 2.0 - phi) * 4.0 / kPi * r;
  } else if (phi < 5.0 * kPi / 4.0) {
    a = -r;
    b = (phi - kPi) * 4.0 / kPi * a;
  } else {
    b = -r;
    a = (3.0 * kPi / 2.0 - phi) * 4.0 / kPi * b;
  }
  return {std::clamp(0.5 * (a + 1.0), 0.0, 1.0), std::clamp(0.5 * (b + 1.0), 0.0, 1.0)};
}

// Vogel's golden-angle spiral (sunflower) on the unit disk, rotated by a seeded angle, mapped to
// the square by the concentric inverse so that a disk light gets the spiral back exactly.
std::vector<glm::dvec2> vogel(int n, Rng& rng) {
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  const double offset = 2.0 * kPi * rng.uniform();
  std::vector<glm::dvec2> pts;
  pts.reserve(n);
  for (int k = 0; k < n; ++k) {
    const double r = std::sqrt((k + 0.5) / n), theta = k * golden + offset;
    pts.push_back(diskToSquare({r * std::cos(theta), r * std::sin(theta)}));
  }
  return pts;
}

std::vector<glm::dvec2> unitPoints(SampleStrategy strategy, int count, std::uint32_t seed) {
  if (count == 1) return {glm::dvec2(0.5)};  // hard shadows: the light centre
  Rng rng(streamSeed(seed, kStreamPoints));
  switch (strategy) {
    case SampleStrategy::Stratified:
      return stratified(count, rng);
    case SampleStrategy::Poisson:
      return poisson(count, rng);
    case SampleStrategy::Vogel:
      return vogel(count, rng);
  }
  return {};
}

// Third coordinate of sphere (ball) samples: stratified in [0,1) with one value per stratum
// [i/N, (i+1)/N), jittered, paired with the 2D points by a seeded permutation (a Latin-hypercube
// dimension). r = R * cbrt(w) then puts exactly one sample in each of N equal-volume shells.
std::vector<double> radialCoordinates(int count, std::uint32_t seed) {
  if (count == 1) return {0.0};  // the centre
  std::vector<double> w(count);
  Rng rng(streamSeed(seed, kStreamRadial));
  for (int i = 0; i < count; ++i) w[i] = (i + rng.uniform()) / count;
  for (int i = count - 1; i > 0; --i) std::swap(w[i], w[rng.below(std::uint32_t(i) + 1)]);
  return w;
}

// ---- the light ---------------------------------------------------------------------------

// Validated light geometry and its emission texture frame.
struct LightMap {
  const Light* light = nullptr;
  glm::dvec3 c, n, t, b;
  const Image* texture = nullptr;  // null: untextured, luminance 1
  double area = 0.0;               // rect w*h, disk pi r^2; for spheres pi R^2 (see header)
};

LightMap makeLightMap(const Scene& scene, const Light& light, float time) {
  LightMap m;
  m.light = &light;
  m.c = glm::dvec3(light.position);
  m.n = glm::dvec3(light.normal);
  m.t = glm::dvec3(light.tangent);
  m.b = glm::dvec3(light.bitangent());
  const glm::vec2 s = light.size;
  auto bad = [](float v) { return !(v > 0.0f) || !std::isfinite(v); };  // catches NaN
  switch (light.shape) {
    case LightShape::Point:
      break;
    case LightShape::Rect:
      if (bad(s.x) || bad(s.y))
        throw Error(light.name, "rect light size must be positive and finite, got " + std::to_string(s.x) + " x " +
                                    std::to_string(s.y));
      m.area = double(s.x) * s.y;
      break;
    case LightShape::Disk:
    case LightShape::Sphere:
      if (bad(s.x)) throw Error(light.name, "light radius must be positive and finite, got " + std::to_string(s.x));
      m.area = kPi * double(s.x) * s.x;
      break;
  }
  if (!light.emissionFrames.empty()) {
    const int frame = light.frameAt(time);
    const int tex = (frame >= 0 && frame < int(light.emissionFrames.size())) ? light.emissionFrames[frame] : -1;
    if (tex < 0 || tex >= int(scene.textures.size()))
      throw Error(light.name, "emission texture index " + std::to_string(tex) + " out of range");
    const Image& img = scene.textures[tex].image;
    if (img.empty() || img.channels < 1)
      throw Error(light.name, "emission texture '" + scene.textures[tex].source + "' is empty");
    m.texture = &img;
  }
  return m;
}

// How set j of a pattern is derived from its base set: a toroidal shift of the unit square
// (rects) or a rotation about the light normal (disks, spheres).
struct SetTransform {
  glm::dvec2 shift{0.0};
  double angle = 0.0;
};

// Maps one unit-square point (+ radial coordinate for spheres) to the light and appends it.
void appendSample(const LightMap& m, glm::dvec2 unit, double radial, const SetTransform& tf, LightSampleSet& out) {
  const Light& light = *m.light;
  glm::dvec3 p = m.c;
  glm::dvec2 uv{0.5};
  switch (light.shape) {
    case LightShape::Point:
      break;
    case LightShape::Rect: {
      // Cranley-Patterson rotation: the shifted points wrap around and stay on the light.
      uv = {fract(unit.x + tf.shift.x), fract(unit.y + tf.shift.y)};
      p += (uv.x - 0.5) * double(light.size.x) * m.t + (uv.y - 0.5) * double(light.size.y) * m.b;
      break;
    }
    case LightShape::Disk: {
      const glm::dvec2 d0 = squareToDisk(unit);
      const double cs = std::cos(tf.angle), sn = std::sin(tf.angle);
      const glm::dvec2 d{cs * d0.x - sn * d0.y, sn * d0.x + cs * d0.y};
      uv = 0.5 + 0.5 * d;  // the disk inscribed in the texture square
      p += double(light.size.x) * (d.x * m.t + d.y * m.b);
      break;
    }
    case LightShape::Sphere: {
      // Uniform ball: direction from (u, v) by the area-preserving cylindrical map (z = 1 - 2v,
      // longitude 2 pi u; a rotation about the normal is a shift of u), radius R cbrt(w).
      const double u = fract(unit.x + tf.angle / (2.0 * kPi));
      const double z = 1.0 - 2.0 * unit.y, sinTheta = std::sqrt(std::max(0.0, 1.0 - z * z));
      const double phi = 2.0 * kPi * u;
      const glm::dvec3 dir = sinTheta * std::cos(phi) * m.t + sinTheta * std::sin(phi) * m.b + z * m.n;
      p += double(light.size.x) * std::cbrt(radial) * dir;
      uv = {u, std::acos(std::clamp(z, -1.0, 1.0)) / kPi};  // longitude / latitude
      break;
    }
  }
  out.positions.push_back(glm::vec3(p));
  out.uv.push_back({unitFloat(uv.x), unitFloat(uv.y)});
  out.luminance.push_back(m.texture ? emissionAt(*m.texture, uv) : glm::vec3(1.0f));
}

void appendSet(const LightMap& m, const std::vector<glm::dvec2>& unit, const std::vector<double>& radial,
               const SetTransform& tf, LightSampleSet& out) {
  for (std::size_t k = 0; k < unit.size(); ++k) appendSample(m, unit[k], radial[k], tf, out);
}

void fillRadiometry(const LightMap& m, LightSampleSet& out) {
  const Light& light = *m.light;
  const bool oneSided = light.shape == LightShape::Rect || light.shape == LightShape::Disk;
  out.lightNormal = oneSided ? glm::normalize(light.normal) : glm::vec3(0.0f);
  out.sampleWeight = light.isArea() ? float(m.area / out.count) : 1.0f;
}

void checkCount(int count, int max, const char* where) {
  if (count < 1 || count > max)
    throw Error(where, "sample count must be in 1.." + std::to_string(max) + ", got " + std::to_string(count));
}

}  // namespace

glm::vec3 emissionAt(const Image& img, glm::dvec2 uv) {
  const double fx = uv.x * img.width - 0.5, fy = uv.y * img.height - 0.5;
  const double x0f = std::floor(fx), y0f = std::floor(fy);
  const double ax = fx - x0f, ay = fy - y0f;
  auto texel = [&](int x, int y) {
    x = std::clamp(x, 0, img.width - 1);
    y = std::clamp(y, 0, img.height - 1);
    if (img.channels < 3) return glm::dvec3(img.at(x, y, 0));
    return glm::dvec3(img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2));
  };
  const int x0 = int(x0f), y0 = int(y0f);
  const glm::dvec3 top = texel(x0, y0) * (1.0 - ax) + texel(x0 + 1, y0) * ax;
  const glm::dvec3 bottom = texel(x0, y0 + 1) * (1.0 - ax) + texel(x0 + 1, y0 + 1) * ax;
  return glm::vec3(top * (1.0 - ay) + bottom * ay);
}

const Image* lightEmissionTexture(const Scene& scene, const Light& light, float time) {
  return makeLightMap(scene, light, time).texture;
}

int LightSampleSet::setForPixel(int x, int y) const {
  return int(shared::penumbraSetForPixel(std::uint32_t(x), std::uint32_t(y), std::uint32_t(pattern),
                                         std::uint32_t(setCount), std::uint32_t(interleaveK), seed));
}

std::vector<glm::vec2> unitSquareSamples(SampleStrategy strategy, int count, std::uint32_t seed) {
  checkCount(count, kMaxSingleSetCount, "samples");
  std::vector<glm::vec2> out;
  out.reserve(count);
  for (const glm::dvec2& p : unitPoints(strategy, count, seed)) out.push_back({unitFloat(p.x), unitFloat(p.y)});
  return out;
}

LightSampleSet makeLightSamples(const Scene& scene, const Light& light, const SamplingParams& params, float time) {
  checkCount(params.count, PENUMBRA_MAX_SAMPLES, "samples");
  if (params.pattern == PixelPattern::Decorrelated &&
      (params.decorrelatedSets < 1 || params.decorrelatedSets > kMaxDecorrelatedSets))
    throw Error("decorrelated sets", "decorrelated set count must be in 1.." + std::to_string(kMaxDecorrelatedSets) +
                                         ", got " + std::to_string(params.decorrelatedSets));
  if (params.pattern == PixelPattern::Interleaved && (params.interleaveK < 1 || params.interleaveK > kMaxInterleaveK))
    throw Error("interleave K", "interleave tile size K must be in 1.." + std::to_string(kMaxInterleaveK) + ", got " +
                                    std::to_string(params.interleaveK));
  const LightMap m = makeLightMap(scene, light, time);

  LightSampleSet out;
  out.shape = light.shape;
  out.seed = params.seed;
  out.strategy = params.strategy;
  // A point light, or one sample (hard shadows), has a single position: every set would be the
  // centre, so the pattern collapses to one correlated set.
  const bool single = light.shape == LightShape::Point || params.count == 1;
  out.count = light.shape == LightShape::Point ? 1 : params.count;
  out.pattern = single ? PixelPattern::Correlated : params.pattern;
  out.setCount = 1;
  out.interleaveK = 1;
  if (!single && out.pattern == PixelPattern::Decorrelated) out.setCount = params.decorrelatedSets;
  if (!single && out.pattern == PixelPattern::Interleaved) {
    out.interleaveK = params.interleaveK;
    out.setCount = params.interleaveK * params.interleaveK;
  }
  const std::size_t total = std::size_t(out.setCount) * out.count;
  out.positions.reserve(total);
  out.uv.reserve(total);
  out.luminance.reserve(total);

  if (out.pattern == PixelPattern::Interleaved) {
    // K*K independently seeded sets (section 5.2); set j uses seed stream j.
    for (int j = 0; j < out.setCount; ++j) {
      const std::uint32_t s = std::uint32_t(streamSeed(params.seed, kStreamPoints, j + 1));
      appendSet(m, unitPoints(params.strategy, out.count, s), radialCoordinates(out.count, s), {}, out);
    }
  } else {
    // Set 0 is the base set; decorrelated set j is it rotated (section 5.1, "randomly rotating
    // the initial sampling pattern") by 2 pi j / M plus a seeded offset within one step, or for
    // rects shifted toroidally by the j-th point of the R2 sequence (Roberts 2018) plus a
    // seeded offset, so the M shifts cover the square evenly.
    const auto unit = unitPoints(params.strategy, out.count, params.seed);
    const auto radial = radialCoordinates(out.count, params.seed);
    Rng rot(streamSeed(params.seed, kStreamRotation));
    const double angleOffset = rot.uniform() * 2.0 * kPi / out.setCount;
    const glm::dvec2 shiftOffset{rot.uniform(), rot.uniform()};
    constexpr double g = 1.32471795724474602596;  // plastic number: R2 = (1/g, 1/g^2)
    for (int j = 0; j < out.setCount; ++j) {
      SetTransform tf;
      if (j > 0) {
        tf.angle = 2.0 * kPi * j / out.setCount + angleOffset;
        tf.shift = {fract(j / g + shiftOffset.x), fract(j / (g * g) + shiftOffset.y)};
      }
      appendSet(m, unit, radial, tf, out);
    }
  }
  fillRadiometry(m, out);
  return out;
}

LightSampleSet makeLightSampleSet(const Scene& scene, const Light& light, SampleStrategy strategy, int count,
                                  std::uint32_t seed, float time) {
  checkCount(count, kMaxSingleSetCount, "reference-samples");
  const LightMap m = makeLightMap(scene, light, time);
  LightSampleSet out;
  out.shape = light.shape;
  out.seed = seed;
  out.strategy = strategy;
  out.count = light.shape == LightShape::Point ? 1 : count;
  out.positions.reserve(out.count);
  out.uv.reserve(out.count);
  out.luminance.reserve(out.count);
  appendSet(m, unitPoints(strategy, out.count, seed), radialCoordinates(out.count, seed), {}, out);
  fillRadiometry(m, out);
  return out;
}

}  // namespace penumbra
