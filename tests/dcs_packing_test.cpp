// Float-base counter packing (DCS eq. 7-10) and the packing planner. No GL.
#include <gtest/gtest.h>

#include <cmath>

#include "techniques/dcs/packing.h"

namespace penumbra::dcs {
namespace {

TEST(DcsPacking, EveryLayoutFillsExactly24Bits) {
  for (const auto& l : kLayouts) EXPECT_EQ(std::pow(double(l.base), l.digits), double(1 << 24)) << l.base;
}

TEST(DcsPacking, FloatAdditionOfPackedDigitsIsExact) {
  // The paper's claim behind eq. 7-10: adding digit * B^d in float keeps every digit exact as
  // long as each stays below B, including temporary negative totals.
  for (const auto& l : kLayouts) {
    if (l.digits == 1) continue;
    float v = 0.0f;
    std::vector<int> digits(std::size_t(l.digits), 0);
    unsigned seed = 12345u;
    for (int step = 0; step < 2000; ++step) {
      seed = seed * 1664525u + 1013904223u;
      int d = int(seed >> 8) % l.digits;
      int delta = digits[std::size_t(d)] == int(l.base) - 1 ? -1 : (digits[std::size_t(d)] == 0 ? 1 : ((seed >> 4) & 1 ? 1 : -1));
      digits[std::size_t(d)] += delta;
      v += float(delta) * float(std::pow(double(l.base), d));
    }
    double rest = v;
    for (int d = 0; d < l.digits; ++d) {
      double q = std::floor(rest / l.base);
      EXPECT_EQ(int(rest - q * l.base), digits[std::size_t(d)]) << "base " << l.base << " digit " << d;
      rest = q;
    }
  }
}

TEST(DcsPacking, PlannerPicksTheNarrowestBaseThatHoldsTheCount) {
  EXPECT_EQ(planPacking(16, 7, 4).counters.base, 8u);
  EXPECT_EQ(planPacking(16, 8, 4).counters.base, 16u);
  EXPECT_EQ(planPacking(16, 63, 4).counters.base, 64u);
  EXPECT_EQ(planPacking(16, 64, 4).counters.base, 256u);
  EXPECT_EQ(planPacking(16, 256, 4).counters.base, 4096u);
  EXPECT_EQ(planPacking(16, 5000, 4).counters.base, 1u << 24);
  EXPECT_EQ(planPacking(16, 1, 4, 2).counters.base, 64u);  // minimum layout honoured
}

TEST(DcsPacking, TargetsAndPassesCoverEverySample) {
  for (int n : {1, 16, 32, 64, 100, 128}) {
    for (int maxCount : {1, 10, 100, 300, 100000}) {
      for (int maxTargets : {1, 4, 7}) {
        PackingPlan p = planPacking(n, maxCount, maxTargets);
        EXPECT_LE(p.targets, maxTargets);
        EXPECT_EQ(p.samplesPerPass, 4 * p.counters.digits * p.targets);
        EXPECT_GE(p.passes * p.samplesPerPass, n);
        EXPECT_LT((p.passes - 1) * p.samplesPerPass, n);
      }
    }
  }
  // The paper's configurations (Table 1): 64 samples in base 64 fit 4 targets in one pass.
  PackingPlan p = planPacking(64, 40, 4);
  EXPECT_EQ(p.counters.base, 64u);
  EXPECT_EQ(p.targets, 4);
  EXPECT_EQ(p.passes, 1);
  // 128 samples in base 8: 32 a target, 4 targets, one pass.
  p = planPacking(128, 5, 4);
  EXPECT_EQ(p.targets, 4);
  EXPECT_EQ(p.passes, 1);
}

// A light's first frame, no bound measured yet, plans for the widest base that costs no more
// targets than base 256 and no extra pass (issue 19 section 3: the bound pass it replaces cost
// 54-70% of a counter pass). 16 samples: base 256 takes 2 targets (12 a target), so does 4096
// (8); 2^24 would take 4. 32 samples: 256 takes 3 targets, 4096 would take 4: 256 stays. 64
// samples: 256 and 4096 need 2 passes, base 64 one (16 a target, 4 targets).
TEST(DcsPacking, WidestPlanWithoutAnExtraPass) {
  PackingPlan p = widestPlanAtTheCostOf(16, 255, 4);
  EXPECT_EQ(p.counters.base, 4096u);
  EXPECT_EQ(p.targets, 2);
  EXPECT_EQ(p.passes, 1);
  EXPECT_EQ(widestPlanAtTheCostOf(32, 255, 4).counters.base, 256u);
  p = widestPlanAtTheCostOf(64, 255, 4);
  EXPECT_EQ(p.counters.base, 64u);
  EXPECT_EQ(p.passes, 1);
  EXPECT_EQ(widestPlanAtTheCostOf(4, 255, 4).counters.base, 1u << 24) << "4 samples: one target in any base";
  for (int n : {1, 7, 16, 24, 32, 48, 64, 100, 128})
    for (int maxTargets : {1, 2, 4, 7})
      for (int count : {3, 60, 255, 4000}) {
        const PackingPlan cost = planPacking(n, count, maxTargets), wide = widestPlanAtTheCostOf(n, count, maxTargets);
        const int fewest = planPacking(n, 0, maxTargets).passes;
        EXPECT_LE(wide.targets, cost.targets);
        EXPECT_EQ(wide.passes, fewest);
        if (wide.layout + 1 < kLayoutCount) {  // the next wider layout costs more
          const PackingPlan next = planPacking(n, int(kLayouts[wide.layout + 1].base - 1), maxTargets);
          EXPECT_TRUE(next.targets > cost.targets || next.passes > fewest) << n << " " << maxTargets << " " << count;
        }
      }
}

}  // namespace
}  // namespace penumbra::dcs
