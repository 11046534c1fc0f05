#include "techniques/denoised/ffx_denoiser.h"

#include <cmath>

namespace penumbra::denoise {
namespace {

constexpr int kTileW = 8, kTileH = 4;

float gray(const Image& im, int x, int y) { return (im.at(x, y, 0) + im.at(x, y, 1) + im.at(x, y, 2)) / 3.0f; }

// Step 1: per pixel, 0 or 1 where its tile and the 8 around are uniformly that (the masks all
// ones or all zeros, and every traced ratio exactly 0 or 1), else -1.
std::vector<int> classifyTiles(const CpuGBuffer& g, const Image& ratio, double& uniformShare) {
  const int tw = (g.width + kTileW - 1) / kTileW, th = (g.height + kTileH - 1) / kTileH;
  // Per tile: its mask, whether every pixel with a surface is exactly 0 or 1, whether it has one.
  std::vector<std::uint32_t> mask(std::size_t(tw) * th, 0), surface(std::size_t(tw) * th, 0);
  std::vector<std::uint8_t> exact(std::size_t(tw) * th, 1);
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const std::size_t i = std::size_t(y) * g.width + x, t = std::size_t(y / kTileH) * tw + std::size_t(x / kTileW);
      if (!g.valid[i]) continue;
      const std::uint32_t bit = 1u << ((y % kTileH) * kTileW + x % kTileW);
      const float v = gray(ratio, x, y);
      surface[t] |= bit;
      if (v >= 0.5f) mask[t] |= bit;
      exact[t] = exact[t] && (v == 0.0f || v == 1.0f);
    }
  std::vector<int> uniform(std::size_t(tw) * th, -1);
  std::size_t tiles = 0, uniformTiles = 0;
  for (int ty = 0; ty < th; ++ty)
    for (int tx = 0; tx < tw; ++tx) {
      const std::size_t t = std::size_t(ty) * tw + tx;
      if (!surface[t]) continue;
      ++tiles;
      bool lit = true, dark = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = tx + dx, ny = ty + dy;
          if (nx < 0 || ny < 0 || nx >= tw || ny >= th) continue;
          const std::size_t u = std::size_t(ny) * tw + nx;
          lit = lit && exact[u] && (mask[u] & surface[u]) == surface[u];
          dark = dark && exact[u] && (mask[u] & surface[u]) == 0u;
        }
      if (lit || dark) uniform[t] = lit ? 1 : 0, ++uniformTiles;
    }
  uniformShare = tiles ? double(uniformTiles) / double(tiles) : 0.0;
  std::vector<int> out(std::size_t(g.width) * g.height, -1);
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x)
      out[std::size_t(y) * g.width + x] = uniform[std::size_t(y / kTileH) * tw + std::size_t(x / kTileW)];
  return out;
}

// The 7 x 7 neighbourhood's mean and variance of the ratio's gray value over surface pixels.
void localMoments(const CpuGBuffer& g, const Image& ratio, std::vector<float>& mean, std::vector<float>& variance) {
  mean.assign(std::size_t(g.width) * g.height, 0.0f);
  variance.assign(mean.size(), 0.0f);
  forEachRow(g.height, [&](int y) {
    for (int x = 0; x < g.width; ++x) {
      const std::size_t i = std::size_t(y) * g.width + x;
      if (!g.valid[i]) continue;
      double s = 0.0, s2 = 0.0;
      int n = 0;
      for (int dy = -3; dy <= 3; ++dy)
        for (int dx = -3; dx <= 3; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= g.width || yy >= g.height || !g.valid[std::size_t(yy) * g.width + xx]) continue;
          const double v = gray(ratio, xx, yy);
          s += v, s2 += v * v, ++n;
        }
      mean[i] = float(s / n);
      variance[i] = float(std::max(s2 / n - (s / n) * (s / n), 0.0));
    }
  });
}

// Step 4: one a-trous pass of step `step` over the pixels to filter.
void atrousPass(const CpuGBuffer& g, const std::vector<int>& uniform, int step, Image& value,
                std::vector<float>& variance) {
  const glm::vec3 eye = g.camera.value_or(glm::vec3(0.0f));
  const Image in = value;
  const std::vector<float> var = variance;
  constexpr float kernel[5] = {1.0f / 16, 1.0f / 4, 3.0f / 8, 1.0f / 4, 1.0f / 16};  // B3 spline
  forEachRow(g.height, [&](int y) {
    for (int x = 0; x < g.width; ++x) {
      const std::size_t i = std::size_t(y) * g.width + x;
      if (!g.valid[i] || uniform[i] >= 0) continue;
      const glm::vec3 p = g.position[i], n = g.normal[i];
      const float tolerance = 0.01f * glm::length(p - eye), vp = gray(in, x, y);
      // The value stop's deviation: the variance blurred over 3 x 3 (a pixel's own is noise).
      double blurred = 0.0, blurWeights = 0.0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= g.width || yy >= g.height || !g.valid[std::size_t(yy) * g.width + xx]) continue;
          const double w = (dx ? 0.5 : 1.0) * (dy ? 0.5 : 1.0);
          blurred += w * var[std::size_t(yy) * g.width + xx], blurWeights += w;
        }
      const float stop = 4.0f * float(std::sqrt(blurred / blurWeights)) + 1e-4f;
      glm::dvec3 sum(0.0);
      double weights = 0.0, varSum = 0.0;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          const int xx = x + dx * step, yy = y + dy * step;
          if (xx < 0 || yy < 0 || xx >= g.width || yy >= g.height) continue;
          const std::size_t j = std::size_t(yy) * g.width + xx;
          if (!g.valid[j]) continue;
          const float nn = std::max(glm::dot(n, g.normal[j]), 0.0f), n2 = nn * nn, n4 = n2 * n2, n8 = n4 * n4;
          const float plane = std::abs(glm::dot(n, g.position[j] - p)) / tolerance;
          const float valueStop = std::abs(gray(in, xx, yy) - vp) / stop;
          const double w =
              double(kernel[dx + 2] * kernel[dy + 2]) * double(n8 * n8) * std::exp(-double(plane + valueStop));
          if (!(w > 1e-9)) continue;
          sum += w * glm::dvec3(in.at(xx, yy, 0), in.at(xx, yy, 1), in.at(xx, yy, 2));
          weights += w;
          varSum += w * w * double(var[j]);
        }
      if (!(weights > 0.0)) continue;
      for (int c = 0; c < 3; ++c) value.at(x, y, c) = float(sum[c] / weights);
      variance[i] = float(varSum / (weights * weights));
    }
  });
}

}  // namespace

Image ffxDenoise(const CpuGBuffer& g, const Camera& camera, const Image& ratio, FfxHistory& h, const FfxOptions& o,
                 FfxStatistics& stats) {
  const std::size_t pixels = std::size_t(g.width) * g.height;
  const glm::vec3 eye = g.camera.value_or(glm::vec3(0.0f));
  const std::vector<int> uniform = classifyTiles(g, ratio, stats.uniformTiles);
  std::vector<float> localMean, localVariance;
  localMoments(g, ratio, localMean, localVariance);

  // Step 2: the history reprojected, disocclusion by depth and normal, clamped, accumulated.
  Image mean = ratio, second(g.width, g.height, 3, 0.0f);
  for (std::size_t k = 0; k < second.data.size(); ++k) second.data[k] = ratio.data[k] * ratio.data[k];
  std::vector<int> length(pixels, 1);
  const bool haveHistory = o.temporal && !h.valid.empty() && h.mean.width == g.width && h.mean.height == g.height;
  const PreviousView previous = previousView(h.camera, h.origin, float(g.width) / float(g.height));
  for (int y = 0; haveHistory && y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const std::size_t i = std::size_t(y) * g.width + x;
      if (!g.valid[i] || uniform[i] >= 0) continue;
      glm::vec3 p;
      const long found = previousPixel(g, i, previous, p);
      if (found < 0) continue;
      const std::size_t j = std::size_t(found);
      const float depth = glm::length(g.position[i] - eye);
      if (!h.valid[j] || std::abs(h.depth[j] - depth) > 0.01f * depth || glm::dot(h.normal[j], g.normal[i]) < 0.9f)
        continue;
      const int px = int(j % std::size_t(g.width)), py = int(j / std::size_t(g.width));
      length[i] = std::min(h.length[j] + 1, o.maxHistory);
      const float sd = std::sqrt(localVariance[i]), lo = localMean[i] - float(o.clampSigma) * sd,
                  hi = localMean[i] + float(o.clampSigma) * sd;
      for (int c = 0; c < 3; ++c) {
        const float oldMean = std::clamp(h.mean.at(px, py, c), lo, hi), v = ratio.at(x, y, c);
        const float oldSecond = std::max(h.second.at(px, py, c), oldMean * oldMean);
        mean.at(x, y, c) = oldMean + (v - oldMean) / float(length[i]);
        second.at(x, y, c) = oldSecond + (v * v - oldSecond) / float(length[i]);
      }
    }

  // Step 3: the variance of the accumulated mean.
  std::vector<float> variance(pixels, 0.0f);
  double historySum = 0.0;
  std::size_t surfaces = 0;
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const std::size_t i = std::size_t(y) * g.width + x;
      if (!g.valid[i]) continue;
      historySum += length[i], ++surfaces;
      const float m = gray(mean, x, y), m2 = gray(second, x, y);
      const float temporal = std::max(m2 - m * m, 0.0f);
      variance[i] = (length[i] < 4 ? localVariance[i] : temporal) / float(length[i]);
    }
  stats.meanHistory = surfaces ? historySum / double(surfaces) : 0.0;

  // Uniform tiles keep their value and restart their history from it.
  for (std::size_t i = 0; i < pixels; ++i)
    if (g.valid[i] && uniform[i] >= 0)
      for (int c = 0; c < 3; ++c)
        mean.data[i * 3 + std::size_t(c)] = second.data[i * 3 + std::size_t(c)] = float(uniform[i]);
  if (o.temporal) {
    h.mean = mean;
    h.second = second;
    h.length = length;
    h.depth.assign(pixels, 0.0f);
    for (std::size_t i = 0; i < pixels; ++i)
      if (g.valid[i]) h.depth[i] = glm::length(g.position[i] - eye);
    h.normal = g.normal;
    h.valid = g.valid;
    h.camera = camera;
    h.origin = g.origin;
  }
  // Step 4: three a-trous passes.
  Image out = mean;
  for (int step : {1, 2, 4}) atrousPass(g, uniform, step, out, variance);
  return out;
}

}  // namespace penumbra::denoise
