// FLIP and HDR-FLIP (core/flip.h) against the behaviour the papers state: identical images give
// 0; green against blue is the largest colour difference (1); the colour error's remapping of
// HyAB distances (checked on uniform images, where the filters change nothing, from the
// tabulated CIELAB values of the sRGB primaries rather than from our own conversion); the
// contrast sensitivity filters hide fine patterns more the farther the viewer (more pixels per
// degree); HDR-FLIP's exposure range (c_start maps the largest luminance to 0.85 through the ACES
// curve, c_stop the median) and its independence of the images' overall scale.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/flip.h"

namespace penumbra {
namespace {

Image uniform(int w, int h, float r, float g, float b) {
  Image img(w, h, 3);
  for (std::size_t i = 0; i < img.pixelCount(); ++i)
    img.data[i * 3] = r, img.data[i * 3 + 1] = g, img.data[i * 3 + 2] = b;
  return img;
}

// Vertical stripes `period` pixels wide, alternating a and b.
Image stripes(int w, int h, int period, const float a[3], const float b[3]) {
  Image img(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = (x / period) % 2 ? b[c] : a[c];
  return img;
}

double centre(const Image& map) { return map.at(map.width / 2, map.height / 2, 0); }

TEST(Flip, IdenticalImagesGiveZero) {
  const float a[3] = {0.9f, 0.2f, 0.1f}, b[3] = {0.05f, 0.4f, 0.7f};
  const Image img = stripes(48, 32, 3, a, b);
  EXPECT_EQ(meanOf(ldrFlip(img, img)), 0.0);
  Image hdr = img;
  for (float& v : hdr.data) v *= 40.0f;
  EXPECT_EQ(meanOf(hdrFlip(hdr, hdr)), 0.0);
}

TEST(Flip, GreenAgainstBlueIsTheLargestColourDifference) {
  const Image map = ldrFlip(uniform(32, 32, 0, 1, 0), uniform(32, 32, 0, 0, 1));
  EXPECT_NEAR(centre(map), 1.0, 1e-5);
  EXPECT_NEAR(meanOf(map), 1.0, 1e-5);  // uniform: no feature difference anywhere, borders included
}

// The colour error of uniform greys: HyAB is the lightness difference; ^0.7, then the paper's
// remap with pc = 0.4, pt = 0.95 and cmax = HyAB(green, blue)^0.7 with the Hunt adjustment,
// from the tabulated CIELAB (D65) of sRGB green (87.735, -86.183, 83.179) and blue
// (32.297, 79.188, -107.860).
TEST(Flip, UniformGreysFollowThePapersRemap) {
  const double gL = 87.735, ga = -86.183 * 0.87735, gb = 83.179 * 0.87735;
  const double bL = 32.297, ba = 79.188 * 0.32297, bb = -107.860 * 0.32297;
  const double cmax = std::pow(std::abs(gL - bL) + std::hypot(ga - ba, gb - bb), 0.7);
  auto remap = [&](double e) {
    return e < 0.4 * cmax ? e * 0.95 / (0.4 * cmax) : 0.95 + (e - 0.4 * cmax) / (0.6 * cmax) * 0.05;
  };
  // Black against white: L* 0 and 100.
  EXPECT_NEAR(centre(ldrFlip(uniform(16, 16, 0, 0, 0), uniform(16, 16, 1, 1, 1))), remap(std::pow(100.0, 0.7)), 2e-3);
  // Linear 0.2 against 0.18: L* = 116 Y^(1/3) - 16.
  auto L = [](double y) { return 116.0 * std::cbrt(y) - 16.0; };
  EXPECT_NEAR(centre(ldrFlip(uniform(16, 16, 0.2f, 0.2f, 0.2f), uniform(16, 16, 0.18f, 0.18f, 0.18f))),
              remap(std::pow(L(0.2) - L(0.18), 0.7)), 2e-3);
  // Symmetric, and a difference the size of 1/255 in lightness is small but not 0.
  const Image p = uniform(16, 16, 0.5f, 0.3f, 0.2f), q = uniform(16, 16, 0.3f, 0.5f, 0.2f);
  EXPECT_NEAR(meanOf(ldrFlip(p, q)), meanOf(ldrFlip(q, p)), 1e-6);
}

// The contrast sensitivity functions (HPG 2020 section 4.1): fine stripes are seen as their
// mean, and the more so the farther the viewer. Red-green stripes one pixel wide against their
// mean colour: the error falls as the pixels per degree grow (the paper's 67 against a viewer
// at a quarter of the distance); coarse stripes (8 px) stay visible at 67.
TEST(Flip, FinePatternsFadeWithViewingDistance) {
  const float red[3] = {0.6f, 0.1f, 0.1f}, green[3] = {0.1f, 0.6f, 0.1f};
  const Image mean = uniform(96, 64, 0.35f, 0.35f, 0.1f);
  const double fine67 = meanOf(ldrFlip(stripes(96, 64, 1, red, green), mean));
  const double fine17 = meanOf(ldrFlip(stripes(96, 64, 1, red, green), mean, 67.02 / 4.0));
  const double coarse67 = meanOf(ldrFlip(stripes(96, 64, 8, red, green), mean));
  std::printf("red-green stripes against their mean: 1 px at 67 ppd %.4f, at 16.8 ppd %.4f; 8 px at 67 ppd %.4f\n",
              fine67, fine17, coarse67);
  EXPECT_LT(fine67, 0.5 * fine17);
  EXPECT_LT(fine67, 0.5 * coarse67);
  EXPECT_GT(coarse67, 0.5);
}

// An edge moved by a pixel: the feature pipeline (edges, points) raises the error at the edge
// above what the filtered colours alone give far from it; a pixel away from both edges the
// images are the same and the error is 0.
TEST(Flip, AMovedEdgeIsSeenWhereItMoved) {
  const float black[3] = {0, 0, 0}, white[3] = {1, 1, 1};
  const Image a = stripes(64, 16, 32, black, white);
  Image b = a;
  for (int y = 0; y < 16; ++y)
    for (int c = 0; c < 3; ++c) b.at(32, y, c) = 0.0f;  // the edge at x = 32 moves to 33
  const Image map = ldrFlip(b, a);
  EXPECT_GT(map.at(32, 8, 0), 0.5);
  EXPECT_LT(map.at(4, 8, 0), 1e-6);
  EXPECT_GT(map.at(32, 8, 0), map.at(40, 8, 0));
}

// HDR-FLIP's exposures (EG 2021 section 3): c_start brings the reference's largest luminance to
// 0.85 after the ACES curve (Narkowicz: x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14)), c_stop
// its median, max(2, ceil(c_stop - c_start)) of them.
TEST(Flip, HdrExposureRange) {
  Image ref = uniform(3, 1, 1.0f / 32.0f, 1.0f / 32.0f, 1.0f / 32.0f);
  for (int c = 0; c < 3; ++c) ref.at(2, 0, c) = 4.0f;  // luminances 1/32, 1/32, 4: median 1/32
  const FlipExposures e = flipExposures(ref);
  auto aces = [](double x) { return x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14); };
  EXPECT_NEAR(aces(std::exp2(e.start) * 4.0), 0.85, 1e-6);
  EXPECT_NEAR(aces(std::exp2(e.stop) / 32.0), 0.85, 1e-6);
  EXPECT_NEAR(e.stop - e.start, 7.0, 1e-6);
  EXPECT_EQ(e.count, 7);
  EXPECT_EQ(flipExposures(uniform(4, 4, 2, 2, 2)).count, 2);  // one luminance: two exposures at it
  EXPECT_EQ(flipExposures(uniform(4, 4, 0, 0, 0)).count, 1);  // black: exposure 0
}

// Scaling both images by the same factor (a light 1000x brighter) changes nothing: the exposures
// follow the reference. An error in the dark parts of an image, invisible at the exposure of its
// bright parts, is found by the longer exposures.
TEST(Flip, HdrIsIndependentOfScaleAndSeesTheDarkParts) {
  // A dim room (0.002) with a bright window (2.0) in a corner; the test image is twice as bright
  // in a box of the room.
  Image ref = uniform(64, 32, 0.002f, 0.002f, 0.002f);
  for (int y = 0; y < 8; ++y)
    for (int x = 56; x < 64; ++x)
      for (int c = 0; c < 3; ++c) ref.at(x, y, c) = 2.0f;
  Image test = ref;
  for (int y = 8; y < 24; ++y)
    for (int x = 8; x < 40; ++x)
      for (int c = 0; c < 3; ++c) test.at(x, y, c) = 0.004f;
  const Image map = hdrFlip(test, ref);
  const double base = meanOf(map);
  for (float s : {1e-3f, 1e3f}) {
    Image rs = ref, ts = test;
    for (float& v : rs.data) v *= s;
    for (float& v : ts.data) v *= s;
    EXPECT_NEAR(meanOf(hdrFlip(ts, rs)), base, 1e-4) << s;
  }
  // Displayed as they are (no exposure) the room is nearly black and the box barely differs.
  const double ldr = ldrFlip(test, ref).at(24, 16, 0);
  std::printf("the box: HDR-FLIP %.4f, LDR-FLIP without exposure %.4f\n", map.at(24, 16, 0), ldr);
  EXPECT_GT(map.at(24, 16, 0), 0.3);
  EXPECT_LT(ldr, 0.1);
  EXPECT_LT(map.at(2, 28, 0), 1e-6);  // far from the box: the same
}

TEST(Flip, NonFiniteInputIsNaNNotZero) {
  Image a = uniform(8, 8, 0.5f, 0.5f, 0.5f), b = a;
  b.at(3, 3, 1) = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(std::isnan(ldrFlip(b, a).at(3, 3, 0)));
  EXPECT_TRUE(std::isnan(hdrFlip(b, a).at(3, 3, 0)));
  EXPECT_TRUE(std::isnan(meanOf(hdrFlip(b, a))));
  EXPECT_THROW(ldrFlip(uniform(8, 8, 0, 0, 0), uniform(8, 9, 0, 0, 0)), Error);
  EXPECT_THROW(ldrFlip(a, a, 0.0), Error);
}

TEST(Flip, HeatMapIsMagma) {
  Image map(3, 1, 1);
  map.data = {0.0f, 0.5f, 1.0f};
  const Image heat = flipHeatMap(map);
  EXPECT_LT(heat.at(0, 0, 0), 0.01f);             // near black
  EXPECT_GT(heat.at(1, 0, 0), heat.at(1, 0, 1));  // the middle: red-purple
  EXPECT_GT(heat.at(2, 0, 1), 0.9f);              // the top: pale yellow
  EXPECT_GT(heat.at(2, 0, 0), heat.at(2, 0, 2));
}

}  // namespace
}  // namespace penumbra
