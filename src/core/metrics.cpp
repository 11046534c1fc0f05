#include "core/metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "core/color.h"
#include "core/error.h"

namespace penumbra {
namespace {

std::string shape(const Image& img) {
  return std::to_string(img.width) + "x" + std::to_string(img.height) + "x" + std::to_string(img.channels);
}

void checkComparable(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height || a.channels != b.channels) {
    throw Error("compare", "image shapes differ: " + shape(a) + " vs " + shape(b));
  }
  if (a.data.size() != a.pixelCount() * a.channels || b.data.size() != b.pixelCount() * b.channels) {
    throw Error("compare", "image data size does not match its dimensions");
  }
}

void checkMask(const std::vector<std::uint8_t>& mask, const Image& img, const char* what) {
  if (!mask.empty() && mask.size() != img.pixelCount()) {
    throw Error("compare", std::string(what) + " mask has " + std::to_string(mask.size()) + " entries for " +
                               std::to_string(img.pixelCount()) + " pixels");
  }
}

// Marks i where some j in [i - r, i + r] is set, for `n` entries `stride` apart: one pass of a
// separable Chebyshev dilation, O(n) regardless of r via a running count of set entries.
void dilate1d(const std::uint8_t* in, std::uint8_t* out, int n, std::size_t stride, int r) {
  int count = 0;
  for (int i = 0; i < std::min(r, n); ++i) count += in[i * stride] != 0;
  for (int i = 0; i < n; ++i) {
    if (i + r < n) count += in[(i + r) * stride] != 0;
    if (i - r - 1 >= 0) count -= in[(i - r - 1) * stride] != 0;
    out[i * stride] = count > 0 ? 1 : 0;
  }
}

// sRGB-encoded control points of matplotlib's 'inferno' at t = 0, 1/8, ..., 1: perceptually
// ordered and monotone in lightness, so larger errors always read as brighter.
constexpr std::array<std::array<float, 3>, 9> kInferno = {{
    {0.001f, 0.000f, 0.014f},
    {0.087f, 0.045f, 0.225f},
    {0.258f, 0.039f, 0.406f},
    {0.416f, 0.090f, 0.433f},
    {0.578f, 0.148f, 0.404f},
    {0.736f, 0.216f, 0.330f},
    {0.865f, 0.317f, 0.226f},
    {0.955f, 0.469f, 0.100f},
    {0.988f, 0.998f, 0.645f},
}};

}  // namespace

std::vector<std::uint8_t> edgeBandMask(const Image& reference, int radius, float threshold) {
  PENUMBRA_CHECK(radius >= 0, "edgeBandMask: negative radius");
  const int w = reference.width, h = reference.height, nc = reference.channels;
  PENUMBRA_CHECK(reference.data.size() == reference.pixelCount() * nc,
                 "edgeBandMask: image data size does not match its dimensions");
  std::vector<std::uint8_t> edge(reference.pixelCount(), 0);
  auto differs = [&](int x0, int y0, int x1, int y1) {
    for (int c = 0; c < nc; ++c) {
      if (std::abs(reference.at(x0, y0, c) - reference.at(x1, y1, c)) > threshold) return true;
    }
    return false;
  };
  // Each differing neighbour pair marks both of its pixels: the edge runs between them.
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y) * w + x;
      if (x + 1 < w && differs(x, y, x + 1, y)) edge[i] = edge[i + 1] = 1;
      if (y + 1 < h && differs(x, y, x, y + 1)) edge[i] = edge[i + w] = 1;
    }
  }
  if (radius == 0 || edge.empty()) return edge;
  std::vector<std::uint8_t> rows(edge.size()), mask(edge.size());
  for (int y = 0; y < h; ++y) {
    dilate1d(&edge[std::size_t(y) * w], &rows[std::size_t(y) * w], w, 1, radius);
  }
  for (int x = 0; x < w; ++x) dilate1d(&rows[x], &mask[x], h, std::size_t(w), radius);
  return mask;
}

ErrorStats compareImages(const Image& a, const Image& b, const std::vector<std::uint8_t>& exclude,
                         const std::vector<std::uint8_t>& valid) {
  checkComparable(a, b);
  checkMask(exclude, a, "exclude");
  checkMask(valid, a, "valid");
  ErrorStats s;
  double sumSq = 0.0, sumAbs = 0.0;
  bool anyNaN = false;
  const double over = 1.0 / 255.0;
  for (std::size_t p = 0; p < a.pixelCount(); ++p) {
    if (!exclude.empty() && exclude[p] != 0) continue;
    if (!valid.empty() && valid[p] == 0) continue;
    bool pixelOver = false;
    for (int c = 0; c < a.channels; ++c) {
      const std::size_t i = p * a.channels + c;
      const double d = std::abs(double(a.data[i]) - double(b.data[i]));
      sumSq += d * d;
      sumAbs += d;
      anyNaN |= std::isnan(d);
      s.maxAbs = std::max(s.maxAbs, d);
      pixelOver |= !(d <= over);  // NaN counts as over: a broken pixel is an error
    }
    s.pixelsOver += pixelOver ? 1 : 0;
    ++s.pixelsCounted;
  }
  if (s.pixelsCounted > 0 && a.channels > 0) {
    const double n = double(s.pixelsCounted) * a.channels;
    s.rmse = std::sqrt(sumSq / n);
    s.meanAbs = sumAbs / n;
  }
  // std::max drops NaN; make it visible in maxAbs like it already is in rmse and meanAbs.
  if (anyNaN) s.maxAbs = std::numeric_limits<double>::quiet_NaN();
  return s;
}

Image errorHeatMap(const Image& a, const Image& b, float scale, const std::vector<std::uint8_t>& exclude) {
  checkComparable(a, b);
  checkMask(exclude, a, "exclude");
  PENUMBRA_CHECK(scale > 0.0f && std::isfinite(scale), "errorHeatMap: scale must be positive");
  // Interpolating the sRGB control points keeps the ramp's perceptual spacing; the image is
  // linear, so each result is decoded once here and re-encoded when written as PNG.
  constexpr int kSegments = int(kInferno.size()) - 1;
  Image out(a.width, a.height, 3, 0.2f);
  for (std::size_t p = 0; p < a.pixelCount(); ++p) {
    if (!exclude.empty() && exclude[p] != 0) continue;
    float err = 0.0f;
    for (int c = 0; c < a.channels; ++c) {
      const std::size_t i = p * a.channels + c;
      const float d = std::abs(a.data[i] - b.data[i]);
      if (!(d <= err)) err = d;  // NaN wins, so broken pixels show at full scale
    }
    float t = err / scale;
    t = t < 1.0f ? t : 1.0f;  // NaN -> 1
    const float pos = t * kSegments;
    const int k = std::min(int(pos), kSegments - 1);
    const float f = pos - float(k);
    for (int c = 0; c < 3; ++c) {
      const float s = kInferno[k][c] + f * (kInferno[k + 1][c] - kInferno[k][c]);
      out.data[p * 3 + c] = srgbToLinear(s);
    }
  }
  return out;
}

}  // namespace penumbra
