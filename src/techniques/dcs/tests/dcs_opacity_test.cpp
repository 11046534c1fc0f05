// Semi-opaque occluders in dcs: the unit coding of opacities (src/techniques/dcs/opacity.h). No GL.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "techniques/dcs/opacity.h"
#include "techniques/dcs/dcs_modes.hpp"

namespace penumbra::dcs {
namespace {

TEST(DcsOpacity, OpaqueScenesUseOneUnitPerOccluder) {
  for (auto mode : {OpacityMode::Sum, OpacityMode::Product}) {
    OpacityCoding c = planOpacity({1.0f, 0.0f, 1.0f}, mode, 1e-3);
    EXPECT_EQ(c.mode, PENUMBRA_DCS_OPACITY_OPAQUE);
    EXPECT_EQ(c.units, (std::vector<int>{1, 0, 1}));
    EXPECT_EQ(transmittance(c, 0.0f), 1.0f);
    EXPECT_EQ(transmittance(c, 1.0f), 0.0f);
    EXPECT_EQ(transmittance(c, -1.0f), 1.0f);  // a negative count reads as 0
  }
}

TEST(DcsOpacity, SumCodingIsExactForMultiplesOfOneOverQ) {
  OpacityCoding half = planOpacity({0.5f}, OpacityMode::Sum, 1e-3);
  EXPECT_EQ(half.mode, PENUMBRA_DCS_OPACITY_SUM);
  EXPECT_EQ(half.opaqueUnits, 2);
  EXPECT_EQ(half.units, std::vector<int>{1});
  OpacityCoding tenths = planOpacity({0.5f, 0.3f, 0.7f, 0.4f, 1.0f, 0.0f}, OpacityMode::Sum, 1e-3);
  EXPECT_EQ(tenths.opaqueUnits, 10);
  EXPECT_EQ(tenths.units, (std::vector<int>{5, 3, 7, 4, 10, 0}));
  EXPECT_LT(tenths.maxLayerError, 1e-6);
  // The paper's sum saturates: two layers of 0.5 block everything, 0.3 + 0.4 lets 0.3 through.
  EXPECT_EQ(transmittance(half, 2.0f), 0.0f);
  EXPECT_NEAR(transmittance(tenths, 7.0f), 0.3f, 1e-6f);
}

TEST(DcsOpacity, ProductCodingKeepsEveryLayerWithinTolerance) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.02f, 0.98f);
  for (double tol : {1e-2, 1.0 / 1024.0}) {
    for (int trial = 0; trial < 50; ++trial) {
      std::vector<float> a = {1.0f, 0.0f};
      for (int k = 0; k < 1 + trial % 5; ++k) a.push_back(u(rng));
      OpacityCoding c = planOpacity(a, OpacityMode::Product, tol);
      ASSERT_EQ(c.mode, PENUMBRA_DCS_OPACITY_PRODUCT);
      EXPECT_LE(c.maxLayerError, tol);
      EXPECT_EQ(c.units[0], c.opaqueUnits);
      EXPECT_EQ(c.units[1], 0);
      for (std::size_t i = 2; i < a.size(); ++i) {
        EXPECT_GE(c.units[i], 1);
        EXPECT_NEAR(transmittance(c, float(c.units[i])), 1.0f - a[i], tol) << a[i];
      }
      // An opaque surface blocks everything; decoding U units and more as 0 costs at most the
      // tolerance (U is the first count whose transmittance is below it).
      EXPECT_EQ(transmittance(c, float(c.opaqueUnits)), 0.0f);
      EXPECT_LE(std::exp(-double(c.opaqueUnits) * c.unitLog), tol * (1.0 + 1e-5));
      EXPECT_GT(transmittance(c, float(c.opaqueUnits - 1)), tol * (1.0 - 1e-5));
    }
  }
}

TEST(DcsOpacity, ProductCodingMultipliesLayers) {
  OpacityCoding c = planOpacity({0.5f, 0.3f, 1.0f}, OpacityMode::Product, 1.0 / 1024.0);
  int h = c.units[0], t = c.units[1];
  EXPECT_NEAR(transmittance(c, float(3 * h)), 0.125f, 3.0f / 1024.0f);
  EXPECT_NEAR(transmittance(c, float(h + 2 * t)), 0.5f * 0.7f * 0.7f, 3.0f / 1024.0f);
  // The sum coding of the same layers saturates instead.
  OpacityCoding s = planOpacity({0.5f, 0.3f, 1.0f}, OpacityMode::Sum, 1.0 / 1024.0);
  EXPECT_EQ(transmittance(s, float(2 * s.units[0])), 0.0f);
}

TEST(DcsOpacity, EveryOccludingSurfaceGetsAUnit) {
  // 1e-5 cannot be coded within the tolerance in a reasonable number of units: it still
  // occludes (one unit), and the coding says how far off it is.
  OpacityCoding c = planOpacity({1e-5f, 1.0f}, OpacityMode::Sum, 1e-7);
  EXPECT_GE(c.units[0], 1);
  EXPECT_GT(c.maxLayerError, 1e-7);
}

// Hard case 30: opacities far below the tolerance. Units of -ln(1 - 3e-9) would make an
// opaque surface 2.3e9 units (past an int: it wrapped to -2^31 and every count went wrong);
// such a surface is within the tolerance of transparent and codes as 0 units instead.
TEST(DcsOpacity, NearlyTransparentSurfacesNeverOcclude) {
  const double tol = 1.0 / 1024.0;
  for (auto mode : {OpacityMode::Sum, OpacityMode::Product}) {
    OpacityCoding c = planOpacity({3e-9f, 1e-7f, 1e-8f, 1.0f}, mode, tol);
    EXPECT_EQ(c.mode, PENUMBRA_DCS_OPACITY_OPAQUE) << "nothing left to code but opaque surfaces";
    EXPECT_EQ(c.units, (std::vector<int>{0, 0, 0, 1}));
    EXPECT_EQ(c.opaqueUnits, 1);
    EXPECT_NEAR(c.maxLayerError, 1e-7, 1e-9) << "the error is the largest dropped opacity";
  }
  // Mixed with surfaces that need units: the unit comes from those (2e-3 is the finest here:
  // U = ceil(ln 1024 / -ln(1 - 2e-3)) = 3463), the nearly transparent ones still get 0.
  OpacityCoding c = planOpacity({1e-7f, 1e-8f, 3e-9f, 2e-3f, 0.5f, 1.0f}, OpacityMode::Product, tol);
  ASSERT_EQ(c.mode, PENUMBRA_DCS_OPACITY_PRODUCT);
  EXPECT_EQ(c.units[0], 0);
  EXPECT_EQ(c.units[1], 0);
  EXPECT_EQ(c.units[2], 0);
  EXPECT_GE(c.units[3], 1);
  EXPECT_EQ(c.units[5], c.opaqueUnits);
  EXPECT_GT(c.opaqueUnits, 3000);
  EXPECT_LT(c.opaqueUnits, 4000);
  EXPECT_LE(c.maxLayerError, tol);
  EXPECT_NEAR(transmittance(c, float(c.units[3])), 1.0f - 2e-3f, tol);
  EXPECT_NEAR(transmittance(c, float(c.units[4])), 0.5f, tol);
}

// However the opacities fall, an opaque surface stays within the unit budget (an int, and
// 16 opaque crossings within the 2^24 a float counter holds exactly).
TEST(DcsOpacity, OpaqueUnitsStayWithinTheBudget) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> near(0.001f, 0.003f), any(0.0f, 1.0f);
  for (double tol : {1.0 / 1024.0, 1e-4, 1e-6, 1e-9}) {
    for (int trial = 0; trial < 40; ++trial) {
      std::vector<float> a = {1.0f, near(rng), any(rng), any(rng) * 1e-6f};
      OpacityCoding c = planOpacity(a, OpacityMode::Product, tol);
      ASSERT_EQ(c.mode, PENUMBRA_DCS_OPACITY_PRODUCT);
      EXPECT_GE(c.opaqueUnits, 1);
      EXPECT_LE(c.opaqueUnits, kMaxOpaqueUnits);
      for (int u : c.units) {
        EXPECT_GE(u, 0);
        EXPECT_LE(u, c.opaqueUnits);
      }
      // The worst layer error is what the coding reports, within the tolerance when the budget
      // allows the unit the tolerance needs (1/1024 always does).
      if (tol >= 1e-4) {
        EXPECT_LE(c.maxLayerError, tol) << a[1] << " " << a[2];
      }
    }
  }
}

}  // namespace
}  // namespace penumbra::dcs
