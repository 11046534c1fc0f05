#include "shading/prefiltered_light.h"

#include <algorithm>
#include <cmath>

#include "sampling/light_samples.h"
#include "shading/shading_shared.hpp"

namespace penumbra::shading {
namespace {

constexpr double kMargin = PENUMBRA_PREFILTER_MARGIN;
constexpr int kSubsamples = 4;      // a texel's light samples: kSubsamples^2
constexpr double kFallback = 1e-3;  // weight of the coarser level where a level's own is small

// The discrete Gaussian of sigma texels, truncated at 4 sigma, summing to 1.
std::vector<double> gaussian(double sigma) {
  const int radius = int(std::ceil(4.0 * sigma));
  std::vector<double> g(std::size_t(2 * radius + 1));
  double sum = 0.0;
  for (int i = -radius; i <= radius; ++i) sum += g[std::size_t(i + radius)] = std::exp(-0.5 * i * i / (sigma * sigma));
  for (double& w : g) w /= sum;
  return g;
}

// One separable pass: out(x, y) = sum_i g(i) in(x - i, y) along x (or y when `columns`), the input
// being zero outside [lo, hi) along that axis (the light's support).
std::vector<glm::dvec4> blur(const std::vector<glm::dvec4>& in, int size, const std::vector<double>& g, int lo, int hi,
                             bool columns) {
  const int radius = int(g.size() / 2);
  std::vector<glm::dvec4> out(in.size(), glm::dvec4(0.0));
  for (int line = 0; line < size; ++line)
    for (int x = 0; x < size; ++x) {
      glm::dvec4 acc(0.0);
      for (int s = std::max(lo, x - radius); s < std::min(hi, x + radius + 1); ++s)
        acc +=
            g[std::size_t(x - s + radius)] * in[columns ? std::size_t(s) * size + line : std::size_t(line) * size + s];
      out[columns ? std::size_t(x) * size + line : std::size_t(line) * size + x] = acc;
    }
  return out;
}

}  // namespace

PrefilteredLight prefilterLight(const Image& emission, bool disk) {
  PrefilteredLight chain;
  const int perUnit = std::clamp(std::max(emission.width, emission.height), 32, 128);
  chain.size = int(std::ceil(perUnit * (1.0 + 2.0 * kMargin)));
  const double texel = (1.0 + 2.0 * kMargin) / chain.size;  // uv per texel
  chain.sigma0 = float(texel);
  chain.levels = 1;
  while (texel * std::ldexp(1.0, chain.levels - 1) < 2.0) ++chain.levels;

  // The light's emission times its support (rgb) and the support (a), box-filtered per texel.
  const int n = chain.size;
  std::vector<glm::dvec4> source(std::size_t(n) * n, glm::dvec4(0.0));
  int lo = n, hi = 0;  // texels touching the light, along either axis (the support is symmetric)
  glm::dvec4 total(0.0);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      glm::dvec4 sum(0.0);
      for (int j = 0; j < kSubsamples; ++j)
        for (int i = 0; i < kSubsamples; ++i) {
          const glm::dvec2 uv = -kMargin + (glm::dvec2(x, y) + (glm::dvec2(i, j) + 0.5) / double(kSubsamples)) * texel;
          const glm::dvec2 d = uv - 0.5;
          const bool inside = disk ? glm::dot(d, d) <= 0.25 : (std::abs(d.x) <= 0.5 && std::abs(d.y) <= 0.5);
          if (inside) sum += glm::dvec4(glm::dvec3(emissionAt(emission, uv)), 1.0);
        }
      sum /= double(kSubsamples * kSubsamples);
      source[std::size_t(y) * n + x] = sum;
      total += sum;
      if (sum.w > 0.0) lo = std::min(lo, x), hi = std::max(hi, x + 1);
    }
  const glm::dvec3 mean = glm::dvec3(total) / total.w;

  chain.texels.resize(std::size_t(chain.levels) * n * n);
  std::vector<glm::dvec3> coarser(std::size_t(n) * n, mean);
  for (int k = chain.levels - 1; k >= 0; --k) {
    const std::vector<double> g = gaussian(std::ldexp(1.0, k));  // sigma0 2^k = 2^k texels
    const std::vector<glm::dvec4> rows = blur(source, n, g, lo, hi, false);
    const std::vector<glm::dvec4> both = blur(rows, n, g, lo, hi, true);
    for (std::size_t i = 0; i < both.size(); ++i) {
      const glm::dvec3 value = (glm::dvec3(both[i]) + kFallback * coarser[i]) / (both[i].w + kFallback);
      coarser[i] = value;
      chain.texels[std::size_t(k) * n * n + i] = glm::vec4(glm::vec3(value), float(both[i].w));
    }
  }
  return chain;
}

glm::vec4 prefilteredLevel(const PrefilteredLight& chain, glm::vec2 uv, int k) {
  // Far outside the chain (or not a number: a degenerate footprint) reads as its edge, as the
  // GPU's clamp to edge does, before any conversion to an index.
  auto edge = [](float t) { return std::isfinite(t) ? std::clamp(t, -1.0f, 2.0f) : 0.5f; };
  const glm::vec2 tc = shared::penumbraPrefilterCoordinates(uv);
  const int n = chain.size;
  const float fx = edge(tc.x) * n - 0.5f, fy = edge(tc.y) * n - 0.5f;
  const float x0f = std::floor(fx), y0f = std::floor(fy);
  const float ax = fx - x0f, ay = fy - y0f;
  auto texel = [&](int x, int y) {
    return chain
        .texels[(std::size_t(k) * n + std::size_t(std::clamp(y, 0, n - 1))) * n + std::size_t(std::clamp(x, 0, n - 1))];
  };
  const int x0 = int(x0f), y0 = int(y0f);
  return glm::mix(glm::mix(texel(x0, y0), texel(x0 + 1, y0), ax),
                  glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), ax), ay);
}

glm::vec3 prefilteredEmission(const PrefilteredLight& chain, glm::vec3 footprint) {
  glm::vec3 num(0.0f);
  float den = 0.0f;
  for (int k = 0; k < chain.levels; ++k) {
    const float w = shared::penumbraPrefilterWeight(footprint.z, chain.sigma0, k, chain.levels);
    const glm::vec4 t = prefilteredLevel(chain, glm::vec2(footprint), k);
    num += w * t.w * glm::vec3(t);
    den += w * t.w;
  }
  return den > 0.0f ? num / den : glm::vec3(prefilteredLevel(chain, glm::vec2(footprint), chain.levels - 1));
}

}  // namespace penumbra::shading
