// Error metrics: known values, masks, the edge band and the heat map ramp.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/error.h"
#include "core/metrics.h"

namespace penumbra {
namespace {

Image ramp(int w, int h, int c) {
  Image img(w, h, c);
  for (std::size_t i = 0; i < img.data.size(); ++i) img.data[i] = float(i % 13) / 13.0f;
  return img;
}

Image shifted(const Image& img, float offset) {
  Image out = img;
  for (float& v : out.data) v += offset;
  return out;
}

// Left half 0, right half 1 (w even): the shadow edge runs between columns w/2-1 and w/2.
Image halfBlackHalfWhite(int w, int h, int c) {
  Image img(w, h, c);
  for (int y = 0; y < h; ++y)
    for (int x = w / 2; x < w; ++x)
      for (int ch = 0; ch < c; ++ch) img.at(x, y, ch) = 1.0f;
  return img;
}

std::vector<int> maskedColumns(const std::vector<std::uint8_t>& mask, int w, int h) {
  std::vector<int> columns;
  for (int x = 0; x < w; ++x) {
    int set = 0;
    for (int y = 0; y < h; ++y) set += mask[std::size_t(y) * w + x];
    EXPECT_TRUE(set == 0 || set == h) << "column " << x << " partially masked";
    if (set == h) columns.push_back(x);
  }
  return columns;
}

TEST(Metrics, IdenticalImagesHaveZeroError) {
  const Image a = ramp(8, 6, 3);
  const ErrorStats s = compareImages(a, a);
  EXPECT_EQ(s.rmse, 0.0);
  EXPECT_EQ(s.meanAbs, 0.0);
  EXPECT_EQ(s.maxAbs, 0.0);
  EXPECT_EQ(s.pixelsOver, 0);
  EXPECT_EQ(s.pixelsCounted, 48);
}

TEST(Metrics, ConstantOffsetGivesKnownValues) {
  const Image a = ramp(8, 6, 3);
  const Image b = shifted(a, 0.1f);
  const ErrorStats s = compareImages(a, b);
  EXPECT_NEAR(s.rmse, 0.1, 1e-6);
  EXPECT_NEAR(s.meanAbs, 0.1, 1e-6);
  EXPECT_NEAR(s.maxAbs, 0.1, 1e-6);
  EXPECT_EQ(s.pixelsOver, 48);
  EXPECT_EQ(s.pixelsCounted, 48);
  EXPECT_EQ(compareImages(a, shifted(a, 0.5f / 255.0f)).pixelsOver, 0);
}

TEST(Metrics, SingleChannelErrorAveragesOverChannels) {
  Image a(2, 1, 2, 0.0f), b(2, 1, 2, 0.0f);
  b.at(0, 0, 1) = 0.4f;  // one of four values
  const ErrorStats s = compareImages(a, b);
  EXPECT_NEAR(s.meanAbs, 0.1, 1e-7);
  EXPECT_NEAR(s.rmse, std::sqrt(0.16 / 4), 1e-7);
  EXPECT_NEAR(s.maxAbs, 0.4, 1e-7);
  EXPECT_EQ(s.pixelsOver, 1);
}

TEST(Metrics, ExclusionAndValidMasksAreRespected) {
  const Image a(4, 1, 1, 0.0f);
  Image b(4, 1, 1, 0.0f);
  b.data = {0.5f, 0.2f, 0.1f, 0.0f};
  const std::vector<std::uint8_t> exclude = {1, 0, 0, 0};
  ErrorStats s = compareImages(a, b, exclude);
  EXPECT_EQ(s.pixelsCounted, 3);
  EXPECT_NEAR(s.maxAbs, 0.2, 1e-7);
  EXPECT_NEAR(s.meanAbs, 0.1, 1e-7);
  EXPECT_EQ(s.pixelsOver, 2);

  const std::vector<std::uint8_t> valid = {1, 0, 1, 1};
  s = compareImages(a, b, {}, valid);
  EXPECT_EQ(s.pixelsCounted, 3);
  EXPECT_NEAR(s.maxAbs, 0.5, 1e-7);

  s = compareImages(a, b, exclude, valid);  // both: only pixels 2 and 3
  EXPECT_EQ(s.pixelsCounted, 2);
  EXPECT_NEAR(s.maxAbs, 0.1, 1e-7);
  EXPECT_NEAR(s.meanAbs, 0.05, 1e-7);

  s = compareImages(a, b, {1, 1, 1, 1});  // nothing counted: zeros, not NaN
  EXPECT_EQ(s.pixelsCounted, 0);
  EXPECT_EQ(s.rmse, 0.0);
  EXPECT_EQ(s.meanAbs, 0.0);
}

TEST(Metrics, NaNPixelsCountAsErrors) {
  const Image a(2, 1, 1, 0.0f);
  Image b = a;
  b.data[1] = std::numeric_limits<float>::quiet_NaN();
  const ErrorStats s = compareImages(a, b);
  EXPECT_TRUE(std::isnan(s.rmse));
  EXPECT_TRUE(std::isnan(s.maxAbs));
  EXPECT_EQ(s.pixelsOver, 1);
}

TEST(Metrics, MismatchedShapesOrMasksThrow) {
  const Image a(4, 4, 3), b(4, 3, 3), c(4, 4, 1);
  for (const Image* other : {&b, &c}) {
    try {
      compareImages(a, *other);
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_EQ(e.where(), "compare");
    }
    EXPECT_THROW(errorHeatMap(a, *other, 1.0f), Error);
  }
  EXPECT_THROW(compareImages(a, a, std::vector<std::uint8_t>(15)), Error);
  EXPECT_THROW(compareImages(a, a, {}, std::vector<std::uint8_t>(17)), Error);
  EXPECT_THROW(errorHeatMap(a, a, 1.0f, std::vector<std::uint8_t>(3)), Error);
}

TEST(Metrics, EdgeBandOfAHalfPlaneIsTwoColumnsPerRadiusStep) {
  const int w = 16, h = 5;
  const Image img = halfBlackHalfWhite(w, h, 3);
  EXPECT_EQ(maskedColumns(edgeBandMask(img, 0), w, h), (std::vector<int>{7, 8}));
  EXPECT_EQ(maskedColumns(edgeBandMask(img, 1), w, h), (std::vector<int>{6, 7, 8, 9}));
  EXPECT_EQ(maskedColumns(edgeBandMask(img, 3), w, h), (std::vector<int>{4, 5, 6, 7, 8, 9, 10, 11}));
  EXPECT_EQ(maskedColumns(edgeBandMask(img, 100), w, h).size(), std::size_t(w));
}

TEST(Metrics, EdgeBandUsesAnyChannelAndTheThreshold) {
  Image img(5, 5, 3, 0.5f);
  img.at(2, 2, 1) = 0.6f;  // one pixel differs in G only
  std::vector<std::uint8_t> mask = edgeBandMask(img, 0, 0.05f);
  std::vector<std::uint8_t> expected(25, 0);
  for (int i : {7, 11, 12, 13, 17}) expected[i] = 1;  // the pixel and its 4-neighbours
  EXPECT_EQ(mask, expected);
  // Radius 1 grows the plus shape by one in Chebyshev distance: everything but the corners.
  mask = edgeBandMask(img, 1, 0.05f);
  for (int i = 0; i < 25; ++i) {
    const bool corner = i == 0 || i == 4 || i == 20 || i == 24;
    EXPECT_EQ(mask[i], corner ? 0 : 1) << i;
  }
  EXPECT_EQ(edgeBandMask(img, 2, 0.2f), std::vector<std::uint8_t>(25, 0));
  EXPECT_EQ(edgeBandMask(Image(3, 3, 1, 1.0f), 1), std::vector<std::uint8_t>(9, 0));
}

TEST(Metrics, EdgeBandExcludesThePenumbraFromStatistics) {
  const int w = 16, h = 4;
  const Image ref = halfBlackHalfWhite(w, h, 1);
  Image tech = ref;
  for (int y = 0; y < h; ++y) tech.at(7, y, 0) = tech.at(8, y, 0) = 0.5f;  // blurred edge
  EXPECT_EQ(compareImages(tech, ref).pixelsOver, 2 * h);
  const ErrorStats s = compareImages(tech, ref, edgeBandMask(ref, 1));
  EXPECT_EQ(s.pixelsCounted, (w - 4) * h);
  EXPECT_EQ(s.maxAbs, 0.0);
}

TEST(Metrics, HeatMapEndpointsAndExcludedGrey) {
  const Image a(4, 1, 1, 0.0f);
  Image b = a;
  b.data = {0.0f, 0.5f, 1.0f, 5.0f};
  const Image heat = errorHeatMap(a, b, 1.0f, {0, 0, 0, 0});
  ASSERT_EQ(heat.channels, 3);
  ASSERT_EQ(heat.width, 4);
  auto luminance = [&](int x) {
    return 0.2126f * heat.at(x, 0, 0) + 0.7152f * heat.at(x, 0, 1) + 0.0722f * heat.at(x, 0, 2);
  };
  for (int c = 0; c < 3; ++c) EXPECT_LT(heat.at(0, 0, c), 0.01f);  // zero error: black
  EXPECT_GT(heat.at(2, 0, 0), 0.9f);                               // full scale: bright
  EXPECT_GT(heat.at(2, 0, 1), 0.9f);
  EXPECT_LT(luminance(0), luminance(1));
  EXPECT_LT(luminance(1), luminance(2));
  for (int c = 0; c < 3; ++c) EXPECT_EQ(heat.at(3, 0, c), heat.at(2, 0, c));  // clamped

  const Image excluded = errorHeatMap(a, b, 1.0f, {0, 1, 0, 1});
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(excluded.at(1, 0, c), 0.2f);
    EXPECT_EQ(excluded.at(3, 0, c), 0.2f);
    EXPECT_EQ(excluded.at(2, 0, c), heat.at(2, 0, c));
  }
}

TEST(Metrics, HeatMapIsMonotoneInLuminance) {
  const int n = 256;
  const Image a(n, 1, 3, 0.0f);
  Image b = a;
  for (int x = 0; x < n; ++x) b.at(x, 0, 1) = float(x) / (n - 1) * 0.01f;  // max channel
  const Image heat = errorHeatMap(a, b, 0.01f);
  float previous = -1.0f;
  for (int x = 0; x < n; ++x) {
    const float y = 0.2126f * heat.at(x, 0, 0) + 0.7152f * heat.at(x, 0, 1) + 0.0722f * heat.at(x, 0, 2);
    EXPECT_GT(y, previous) << x;
    previous = y;
  }
}

}  // namespace
}  // namespace penumbra
