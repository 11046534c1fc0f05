// `evsm` against the Embree reference with the same light samples, beside vssm and msm-soft.
#include "render_test_util.h"
#include "techniques/evsm/evsm.h"

namespace penumbra::test {
namespace {

// evsm in vssm's PCSS summed-area framework: the parallel-planes case as
// vssm and msm-soft (measured 0.0144), and less light bleeding than vssm, more than msm-soft
// (measured at 128 px: engine 0.078, sphere grid 0.218, two plates 0.057; vssm 0.112, 0.263,
// 0.079). The exponents (defaults c+ = 40, c- = 10) trade: at 80 / 40 the engine and the sphere
// grid get worse (0.086, 0.243) and the two plates better (0.050); at 160 / 160 0.268 and 0.292.
TEST(Evsm, ParallelPlanesAndBleedingAgainstVssm) {
  Scene square = loadScene(scenePath("scenes/hard/23-analytic-square.json"));
  Comparison r = renderAndCompare(square, "evsm", settings(128, 16));
  EXPECT_LE(r.errors.visibility.rmse, 0.018);
  EXPECT_EQ(statistic(r.frame, "positive exponent"), 40.0);
  EXPECT_EQ(statistic(r.frame, "negative exponent"), 10.0);
  expectBleedsLessThanVssm("evsm",
                           {{"scenes/engine.json", 0.09},
                            {"scenes/hard/15-sphere-grid.json", 0.24},
                            {"scenes/hard/15-two-plates.json", 0.065}},
                           0.9);
}

// The exponent's overflow limits: a table of N texels holds sums up to N exp(2 c). An fp32 table
// of 1024^2 takes c <= 37.06, doubles 175.7 (the float exp of c / 2); beyond, the exponent is
// clamped with a warning and the image stays finite (the renderer refuses NaN) and close to the
// clamped exponent's own.
TEST(Evsm, AnExponentBeyondTheTablesRangeIsClampedNotNaN) {
  EXPECT_NEAR(evsmExponentLimit(32, 1024.0 * 1024.0), 37.06, 0.01);
  EXPECT_NEAR(evsmExponentLimit(64, 1024.0 * 1024.0), 175.7, 0.1);
  Scene scene = loadScene(scenePath("scenes/hard/23-analytic-square.json"));
  Comparison fp32 =
      renderAndCompare(scene, "evsm", settings(96, 16),
                       TechniqueParams({"sat-bits=32", "positive-exponent=200", "negative-exponent=200", "map=256"}));
  EXPECT_NEAR(statistic(fp32.frame, "positive exponent"), evsmExponentLimit(32, 256.0 * 256.0), 1e-6);
  EXPECT_NEAR(statistic(fp32.frame, "negative exponent"), evsmExponentLimit(32, 256.0 * 256.0), 1e-6);
  Comparison doubles = renderAndCompare(scene, "evsm", settings(96, 16), TechniqueParams({"positive-exponent=400"}));
  EXPECT_NEAR(statistic(doubles.frame, "positive exponent"), 175.7, 0.1);
  std::printf("fp32 table at the clamped exponent %.2f: RMSE %.4f; doubles at %.1f: %.4f\n",
              statistic(fp32.frame, "positive exponent"), fp32.errors.visibility.rmse,
              statistic(doubles.frame, "positive exponent"), doubles.errors.visibility.rmse);
  EXPECT_LE(doubles.errors.visibility.rmse, 0.02);  // measured 0.0140
  EXPECT_LE(fp32.errors.visibility.rmse, 0.02);     // measured 0.0152
}

}  // namespace
}  // namespace penumbra::test
