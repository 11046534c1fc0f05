#include "core/flip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>

#include "core/color.h"
#include "core/error.h"

namespace penumbra {
namespace {

constexpr double kPi = 3.14159265358979323846;

// One channel of an image, row-major.
using Plane = std::vector<float>;

// Linear sRGB (D65) <-> CIE XYZ (IEC 61966-2-1).
std::array<double, 3> rgbToXyz(double r, double g, double b) {
  return {0.4124564 * r + 0.3575761 * g + 0.1804375 * b, 0.2126729 * r + 0.7151522 * g + 0.0721750 * b,
          0.0193339 * r + 0.1191920 * g + 0.9503041 * b};
}
std::array<double, 3> xyzToRgb(double x, double y, double z) {
  return {3.2404542 * x - 1.5371385 * y - 0.4985314 * z, -0.9692660 * x + 1.8760108 * y + 0.0415560 * z,
          0.0556434 * x - 0.2040259 * y + 1.0572252 * z};
}
const std::array<double, 3> kWhite = rgbToXyz(1.0, 1.0, 1.0);  // the reference white, linear RGB (1, 1, 1)

// CIELAB of linear RGB with the Hunt adjustment (HPG 2020 section 4.1: a* and b* scaled by
// 0.01 L*, chroma fades with lightness).
struct Lab {
  double L, a, b;
};
Lab huntLab(double r, double g, double b) {
  const auto xyz = rgbToXyz(r, g, b);
  auto f = [](double t) {
    constexpr double d = 6.0 / 29.0;
    return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
  };
  const double fx = f(xyz[0] / kWhite[0]), fy = f(xyz[1] / kWhite[1]), fz = f(xyz[2] / kWhite[2]);
  const double L = 116.0 * fy - 16.0;
  return {L, 0.01 * L * 500.0 * (fx - fy), 0.01 * L * 200.0 * (fy - fz)};
}

// HyAB (Abasi et al. 2020): city-block lightness, Euclidean chroma.
double hyab(const Lab& p, const Lab& q) { return std::abs(p.L - q.L) + std::hypot(p.a - q.a, p.b - q.b); }

// The colour error's constants (HPG 2020 section 4.1).
constexpr double kColourPower = 0.7, kPc = 0.4, kPt = 0.95, kFeaturePower = 0.5;
const double kColourMax = std::pow(hyab(huntLab(0.0, 1.0, 0.0), huntLab(0.0, 0.0, 1.0)), kColourPower);

// Correlates each row (alongX) or column with `k` (odd length, centred), clamping at the borders
// (the clamps only where the kernel reaches past them).
Plane convolve(const Plane& in, int w, int h, const std::vector<double>& k, bool alongX) {
  Plane out(in.size());
  const int r = int(k.size() / 2), n = alongX ? w : h, lines = alongX ? h : w;
  const std::size_t step = alongX ? 1 : std::size_t(w), lineStep = alongX ? std::size_t(w) : 1;
  std::vector<float> kf(k.begin(), k.end());
  for (int l = 0; l < lines; ++l) {
    const float* src = in.data() + std::size_t(l) * lineStep;
    float* dst = out.data() + std::size_t(l) * lineStep;
    for (int i = 0; i < n; ++i) {
      float sum = 0.0f;
      if (i >= r && i + r < n) {
        const float* p = src + std::size_t(i - r) * step;
        for (int j = 0; j <= 2 * r; ++j) sum += kf[std::size_t(j)] * p[std::size_t(j) * step];
      } else {
        for (int j = -r; j <= r; ++j)
          sum += kf[std::size_t(j + r)] * src[std::size_t(std::clamp(i + j, 0, n - 1)) * step];
      }
      dst[std::size_t(i) * step] = sum;
    }
  }
  return out;
}
Plane separable(const Plane& in, int w, int h, const std::vector<double>& kx, const std::vector<double>& ky) {
  return convolve(convolve(in, w, h, kx, true), w, h, ky, false);
}

// The contrast sensitivity functions as sums of Gaussians in frequency, a1 exp(-b1 f^2) +
// a2 exp(-b2 f^2) (HPG 2020 table 1), whose spatial form is sum_i a_i sqrt(pi / b_i)
// exp(-pi^2 x^2 / b_i), x in degrees; each filter normalised to sum 1.
struct Csf {
  double a1, b1, a2, b2;
};
constexpr Csf kAchromatic{1.0, 0.0047, 0.0, 1e-5}, kRedGreen{1.0, 0.0053, 0.0, 1e-5},
    kBlueYellow{34.1, 0.04, 13.5, 0.025};

Plane csfFilter(const Plane& in, int w, int h, const Csf& c, double ppd) {
  // One radius for all three, from the widest Gaussian (b = 0.04): 3 standard deviations.
  const int r = int(std::ceil(3.0 * std::sqrt(0.04 / (2.0 * kPi * kPi)) * ppd));
  auto gaussian = [&](double b, double& sum) {
    std::vector<double> g(std::size_t(2 * r + 1));
    sum = 0.0;
    for (int i = -r; i <= r; ++i) sum += g[std::size_t(i + r)] = std::exp(-kPi * kPi * (i / ppd) * (i / ppd) / b);
    return g;
  };
  double s1 = 0.0, s2 = 0.0;
  const auto g1 = gaussian(c.b1, s1);
  const double w1 = c.a1 * std::sqrt(kPi / c.b1);
  Plane out = separable(in, w, h, g1, g1);
  double norm = w1 * s1 * s1;
  if (c.a2 > 0.0) {
    const auto g2 = gaussian(c.b2, s2);
    const double w2 = c.a2 * std::sqrt(kPi / c.b2);
    const Plane second = separable(in, w, h, g2, g2);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = float(w1 * out[i] + w2 * second[i]);
    norm += w2 * s2 * s2;
    for (auto& v : out) v = float(v / norm);
  } else {
    for (auto& v : out) v = float(v / (s1 * s1));
  }
  return out;
}

// Edge and point magnitudes of a luminance plane (HPG 2020 section 4.2): the first and second
// derivatives of a Gaussian of sigma = 0.5 * 0.082 degrees along x (and y), the Gaussian itself
// across; each derivative kernel's positive weights normalised to sum 1 and its negative ones
// to -1, the Gaussian to 1.
struct Features {
  Plane edges, points;
};
Features features(const Plane& luminance, int w, int h, double ppd) {
  const double sigma = 0.5 * 0.082 * ppd;
  const int r = int(std::ceil(3.0 * sigma));
  std::vector<double> g, d1, d2;
  for (int i = -r; i <= r; ++i) {
    const double x = i, e = std::exp(-x * x / (2.0 * sigma * sigma));
    g.push_back(e), d1.push_back(-x * e), d2.push_back((x * x / (sigma * sigma) - 1.0) * e);
  }
  auto normalise = [](std::vector<double>& k) {
    double pos = 0.0, neg = 0.0;
    for (double v : k) (v > 0 ? pos : neg) += v;
    for (double& v : k) v = v > 0 ? v / pos : (neg < 0 ? v / -neg : v);
  };
  normalise(g), normalise(d1), normalise(d2);
  // The Gaussian across is shared: along y for the x derivatives, along x for the y ones.
  const Plane gy = convolve(luminance, w, h, g, false), gx = convolve(luminance, w, h, g, true);
  const Plane ex = convolve(gy, w, h, d1, true), px = convolve(gy, w, h, d2, true);
  const Plane ey = convolve(gx, w, h, d1, false), py = convolve(gx, w, h, d2, false);
  Features f{Plane(luminance.size()), Plane(luminance.size())};
  for (std::size_t i = 0; i < luminance.size(); ++i) {
    f.edges[i] = std::hypot(ex[i], ey[i]);
    f.points[i] = std::hypot(px[i], py[i]);
  }
  return f;
}

// An image's colour after the CSF filters (Hunt-adjusted CIELAB per pixel) and its features.
struct Perceived {
  std::vector<Lab> colour;
  Features feature;
};
Perceived perceive(const Image& img, double ppd) {
  const int w = img.width, h = img.height;
  const std::size_t n = img.pixelCount();
  Plane Y(n), Cx(n), Cz(n), luminance(n);
  for (std::size_t i = 0; i < n; ++i) {
    const float* p = &img.data[i * std::size_t(img.channels)];
    const auto xyz = rgbToXyz(std::clamp(p[0], 0.0f, 1.0f), std::clamp(p[1], 0.0f, 1.0f), std::clamp(p[2], 0.0f, 1.0f));
    const double x = xyz[0] / kWhite[0], y = xyz[1] / kWhite[1], z = xyz[2] / kWhite[2];
    Y[i] = float(116.0 * y - 16.0), Cx[i] = float(500.0 * (x - y)), Cz[i] = float(200.0 * (y - z));
    luminance[i] = float(y);  // the feature pipeline's achromatic channel, (Y + 16) / 116
  }
  const Plane fY = csfFilter(Y, w, h, kAchromatic, ppd), fCx = csfFilter(Cx, w, h, kRedGreen, ppd),
              fCz = csfFilter(Cz, w, h, kBlueYellow, ppd);
  Perceived out{std::vector<Lab>(n), features(luminance, w, h, ppd)};
  for (std::size_t i = 0; i < n; ++i) {
    const double y = (fY[i] + 16.0) / 116.0, x = fCx[i] / 500.0 + y, z = y - fCz[i] / 200.0;
    const auto rgb = xyzToRgb(x * kWhite[0], y * kWhite[1], z * kWhite[2]);
    out.colour[i] = huntLab(std::clamp(rgb[0], 0.0, 1.0), std::clamp(rgb[1], 0.0, 1.0), std::clamp(rgb[2], 0.0, 1.0));
  }
  return out;
}

void checkPair(const Image& test, const Image& reference, const char* what) {
  if (test.width != reference.width || test.height != reference.height || test.channels < 3 || reference.channels < 3 ||
      test.empty())
    throw Error(what, "needs two RGB images of the same size");
}

// Narkowicz's fit of the ACES filmic curve (HDR-FLIP's default tone mapper) and the input it
// maps to `t`: the positive root of (t k3 - k0) x^2 + (t k4 - k1) x + t k5 = 0. His 0.6
// pre-exposure is left out: HDR-FLIP's exposures are solved through the same curve, so it
// would only shift c_start and c_stop by log2(0.6) and give the same images.
constexpr double kK0 = 2.51, kK1 = 0.03, kK3 = 2.43, kK4 = 0.59, kK5 = 0.14;
double aces(double x) { return std::clamp(x * (kK0 * x + kK1) / (x * (kK3 * x + kK4) + kK5), 0.0, 1.0); }
double acesInverse(double t) {
  const double a = t * kK3 - kK0, b = t * kK4 - kK1, c = t * kK5;
  return (-b - std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a);  // a < 0 for t < k0 / k3: the positive root
}

Image exposed(const Image& img, double c) {
  Image out(img.width, img.height, 3);
  const double scale = std::exp2(c);
  for (std::size_t i = 0; i < img.pixelCount(); ++i)
    for (int k = 0; k < 3; ++k)
      out.data[i * 3 + std::size_t(k)] =
          float(aces(scale * std::max(0.0f, img.data[i * std::size_t(img.channels) + std::size_t(k)])));
  return out;
}

// A pixel where either image is not finite is NaN in the map (never a silent 0: the clamps and
// the exposures would otherwise swallow it).
void markNonFinite(Image& map, const Image& test, const Image& reference) {
  for (std::size_t i = 0; i < map.pixelCount(); ++i)
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(test.data[i * std::size_t(test.channels) + std::size_t(k)]) ||
          !std::isfinite(reference.data[i * std::size_t(reference.channels) + std::size_t(k)]))
        map.data[i] = std::numeric_limits<float>::quiet_NaN();
}

// The LDR-FLIP map of two perceived images.
Image flipOf(const Perceived& t, const Perceived& r, int w, int h) {
  Image map(w, h, 1);
  const double knee = kPc * kColourMax;
  for (std::size_t i = 0; i < map.data.size(); ++i) {
    double colour = std::pow(hyab(t.colour[i], r.colour[i]), kColourPower);
    colour = colour < knee ? colour * kPt / knee : kPt + (colour - knee) / (kColourMax - knee) * (1.0 - kPt);
    const double feature = std::max(std::abs(t.feature.edges[i] - r.feature.edges[i]),
                                    std::abs(t.feature.points[i] - r.feature.points[i]));
    const double f = std::pow(std::min(1.0, feature / std::sqrt(2.0)), kFeaturePower);
    map.data[i] = float(std::pow(std::min(1.0, colour), 1.0 - f));
  }
  return map;
}

void checkPpd(double ppd) {
  if (!(ppd > 0.0) || !std::isfinite(ppd)) throw Error("FLIP", "pixels per degree must be positive and finite");
}

}  // namespace

Image ldrFlip(const Image& test, const Image& reference, double ppd) {
  checkPair(test, reference, "FLIP");
  checkPpd(ppd);
  Image map = flipOf(perceive(test, ppd), perceive(reference, ppd), test.width, test.height);
  markNonFinite(map, test, reference);
  return map;
}

FlipExposures flipExposures(const Image& reference) {
  std::vector<float> luminance;
  float largest = 0.0f;
  for (std::size_t i = 0; i < reference.pixelCount(); ++i) {
    const float* p = &reference.data[i * std::size_t(reference.channels)];
    const float y = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
    if (!(y > 0.0f)) continue;
    largest = std::max(largest, y);
    luminance.push_back(y);
  }
  FlipExposures e;
  if (luminance.empty()) return e;  // black everywhere: exposure 0
  auto mid = luminance.begin() + std::ptrdiff_t(luminance.size() / 2);
  std::nth_element(luminance.begin(), mid, luminance.end());
  const double top = acesInverse(0.85);
  e.start = std::log2(top / double(largest));
  e.stop = std::log2(top / double(*mid));
  e.count = std::max(2, int(std::ceil(e.stop - e.start)));
  return e;
}

struct HdrFlipReference::Impl {
  Image reference;
  double ppd;
  FlipExposures exposures;
  std::vector<double> c;             // each exposure's log2 scale
  std::vector<Perceived> perceived;  // the reference at each
};

HdrFlipReference::HdrFlipReference(const Image& reference, double ppd) : impl_(std::make_unique<Impl>()) {
  if (reference.channels < 3 || reference.empty()) throw Error("HDR-FLIP", "needs an RGB reference image");
  checkPpd(ppd);
  impl_->reference = reference, impl_->ppd = ppd;
  const FlipExposures& e = impl_->exposures = flipExposures(reference);
  for (int k = 0; k < e.count; ++k) {
    impl_->c.push_back(e.count == 1 ? e.start : e.start + (e.stop - e.start) * k / double(e.count - 1));
    impl_->perceived.push_back(perceive(exposed(reference, impl_->c.back()), ppd));
  }
}
HdrFlipReference::~HdrFlipReference() = default;
HdrFlipReference::HdrFlipReference(HdrFlipReference&&) noexcept = default;

const FlipExposures& HdrFlipReference::exposures() const { return impl_->exposures; }

Image HdrFlipReference::against(const Image& test) const {
  const Image& ref = impl_->reference;
  checkPair(test, ref, "HDR-FLIP");
  Image map(test.width, test.height, 1);
  for (std::size_t k = 0; k < impl_->c.size(); ++k) {
    const Image one =
        flipOf(perceive(exposed(test, impl_->c[k]), impl_->ppd), impl_->perceived[k], test.width, test.height);
    for (std::size_t i = 0; i < map.data.size(); ++i) map.data[i] = std::max(map.data[i], one.data[i]);
  }
  markNonFinite(map, test, ref);
  return map;
}

Image hdrFlip(const Image& test, const Image& reference, double ppd, FlipExposures* used) {
  HdrFlipReference r(reference, ppd);
  if (used) *used = r.exposures();
  return r.against(test);
}

double meanOf(const Image& map, const std::vector<std::uint8_t>& valid) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < map.pixelCount(); ++i) {
    if (!valid.empty() && !valid[i]) continue;
    sum += map.data[i * std::size_t(map.channels)];
    ++n;
  }
  return n ? sum / double(n) : 0.0;
}

Image flipHeatMap(const Image& map) {
  // matplotlib's magma (van der Walt and Smith, CC0), sRGB-encoded, at 17 even steps.
  static const float magma[17][3] = {
      {0.0015f, 0.0005f, 0.0139f}, {0.0396f, 0.0311f, 0.1335f}, {0.1131f, 0.0655f, 0.2768f},
      {0.2117f, 0.0620f, 0.4186f}, {0.3167f, 0.0717f, 0.4854f}, {0.4147f, 0.1104f, 0.5047f},
      {0.5128f, 0.1482f, 0.5076f}, {0.6136f, 0.1818f, 0.4985f}, {0.7164f, 0.2150f, 0.4753f},
      {0.8169f, 0.2559f, 0.4365f}, {0.9043f, 0.3196f, 0.3881f}, {0.9609f, 0.4183f, 0.3596f},
      {0.9867f, 0.5356f, 0.3822f}, {0.9961f, 0.6537f, 0.4462f}, {0.9969f, 0.7696f, 0.5349f},
      {0.9924f, 0.8843f, 0.6401f}, {0.9871f, 0.9914f, 0.7495f}};
  Image out(map.width, map.height, 3);
  for (std::size_t i = 0; i < map.pixelCount(); ++i) {
    const float v = std::clamp(map.data[i * std::size_t(map.channels)], 0.0f, 1.0f) * 16.0f;
    const int k = std::min(15, int(v));
    const float f = v - float(k);
    for (int c = 0; c < 3; ++c)
      out.data[i * 3 + std::size_t(c)] = srgbToLinear(magma[k][c] + f * (magma[k + 1][c] - magma[k][c]));
  }
  return out;
}

}  // namespace penumbra
