// Float-base counter packing (DCS eq. 7-10) and the packing planner. No GL.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "techniques/dcs/counter_planner.h"
#include "techniques/dcs/packing.h"

namespace penumbra::dcs {
namespace {

TEST(DcsPacking, EveryLayoutHoldsAsManyDigitsAs24BitsAllow) {
  for (const auto& l : kLayouts) {
    EXPECT_LE(std::pow(double(l.base), l.digits), double(1 << 24)) << l.base;
    EXPECT_GT(std::pow(double(l.base), l.digits + 1), double(1 << 24)) << l.base;
    EXPECT_TRUE(exactWhileCounting(l.base, l.digits, std::int64_t(l.base) - 1)) << "the paper's rule, base " << l.base;
  }
}

// Partial counts may pass their digit (carry into the next, borrow back)
// when the channel's partial sums stay exact; the final value decodes to the final counts.
// Each step adds +-1 to a random digit, the partial counts wander in [-reach, reach], the last
// steps walk every count back into [0, base).
TEST(DcsPacking, PartialCountsPastTheDigitDecodeExactlyWhereThePlanSaysSo) {
  for (const auto& l : kLayouts) {
    if (l.digits == 1) continue;
    const std::int64_t reach = 4 * std::int64_t(l.base);
    int digits = l.digits;
    while (digits > 0 && !exactWhileCounting(l.base, digits, reach)) --digits;
    if (digits < 2) continue;  // 4096: one digit at this reach
    float v = 0.0f;
    std::vector<int> counts(std::size_t(digits), 0);
    unsigned seed = 777u;
    int passedTheDigit = 0;
    auto add = [&](int d, int delta) {
      counts[std::size_t(d)] += delta;
      v += float(delta) * float(std::pow(double(l.base), d));
      passedTheDigit += counts[std::size_t(d)] >= int(l.base) || counts[std::size_t(d)] < 0;
    };
    for (int step = 0; step < 20000; ++step) {
      seed = seed * 1664525u + 1013904223u;
      int d = int(seed >> 8) % digits;
      int c = counts[std::size_t(d)];
      add(d, c >= reach ? -1 : (c <= -reach ? 1 : ((seed >> 4) & 1 ? 1 : -1)));
    }
    for (int d = 0; d < digits; ++d)
      while (counts[std::size_t(d)] < 0 || counts[std::size_t(d)] >= int(l.base))
        add(d, counts[std::size_t(d)] < 0 ? 1 : -1);
    EXPECT_GT(passedTheDigit, 100) << "base " << l.base << ": the walk passed the digits";
    double rest = v;
    for (int d = 0; d < digits; ++d) {
      double q = std::floor(rest / l.base);
      EXPECT_EQ(int(rest - q * l.base), counts[std::size_t(d)]) << "base " << l.base << " digit " << d;
      rest = q;
    }
    EXPECT_EQ(rest, 0.0);
  }
  // The boundary: 496 * (1 + 32 + 32^2 + 32^3) = 2^24 - 16, 497 passes 2^24; 4 digits of base
  // 64 at 263 are past it too.
  EXPECT_TRUE(exactWhileCounting(32, 4, 263));
  EXPECT_TRUE(exactWhileCounting(32, 4, 496));
  EXPECT_FALSE(exactWhileCounting(32, 4, 497));
  EXPECT_FALSE(exactWhileCounting(64, 4, 263));
  EXPECT_TRUE(exactWhileCounting(64, 3, 263));
  EXPECT_FALSE(exactWhileCounting(8, 8, -1));
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
      int delta = digits[std::size_t(d)] == int(l.base) - 1
                      ? -1
                      : (digits[std::size_t(d)] == 0 ? 1 : ((seed >> 4) & 1 ? 1 : -1));
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
  EXPECT_EQ(planPacking(16, 1, 4, 3).counters.base, 64u);  // minimum layout honoured
  for (int maxCount : {0, 5, 30, 200, 3000}) {             // the paper's rule: no carries
    const PackingPlan p = planPacking(16, maxCount, 4);
    EXPECT_FALSE(p.mayCarry()) << maxCount;
    EXPECT_EQ(p.reach, maxCount);
  }
}

// The engine's counts end at 29 (with the bias) but pass 263 on the way.
// The paper's rule packs base 4096 (2 a channel: 16 samples in 2 targets, 64 in 2 passes);
// holding the final counts, with the partial sums exact, packs base 32 (4 a channel: 1 target,
// 64 samples in 4 targets and one pass).
TEST(DcsPacking, PlannerHoldsTheFinalCountsWithExactPartialSums) {
  PackingPlan paper = planPacking(16, 265, 4), p = planPacking(16, 29, 4, 0, 265);
  EXPECT_EQ(paper.counters.base, 4096u);
  EXPECT_EQ(paper.targets, 2);
  EXPECT_EQ(p.counters.base, 32u);
  EXPECT_EQ(p.counters.digits, 4);
  EXPECT_EQ(p.targets, 1);
  EXPECT_TRUE(p.mayCarry());
  EXPECT_TRUE(p.holds(265));
  EXPECT_FALSE(p.holds(497)) << "past the exact partial sums: the pass is redone";
  EXPECT_EQ(planPacking(64, 265, 4).passes, 2);
  p = planPacking(64, 29, 4, 0, 265);
  EXPECT_EQ(p.counters.base, 32u);
  EXPECT_EQ(p.targets, 4);
  EXPECT_EQ(p.passes, 1);
  // Every plan: the final counts fit their digits, the partial sums and the weighted checksum
  // stay exact at the reach, and it costs no more than the paper's rule.
  for (int n : {1, 16, 32, 64, 100, 128})
    for (int maxTargets : {1, 4, 7})
      for (int maxCount : {2, 10, 29, 100, 300})
        for (std::int64_t reach : {0, 30, 265, 1000, 20000}) {
          const PackingPlan q = planPacking(n, maxCount, maxTargets, 0, reach);
          const PackingPlan r = planPacking(n, int(std::max<std::int64_t>(reach, maxCount)), maxTargets);
          EXPECT_GE(std::int64_t(q.counters.base) - 1, maxCount);
          EXPECT_TRUE(exactWhileCounting(q.counters.base, q.counters.digits, q.reach));
          EXPECT_TRUE(q.holds(q.reach));
          if (q.mayCarry()) {
            EXPECT_TRUE(weightedChecksumExact(q.samplesPerPass, q.reach));
          }
          EXPECT_LE(std::pair(q.passes, q.targets), std::pair(r.passes, r.targets))
              << n << " " << maxCount << " " << reach;
          EXPECT_GE(q.passes * q.samplesPerPass, n);
        }
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
// targets than base 256 and no extra pass (the bound pass it replaces cost
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

// Partial counts grow with the samples a pass holds (engine, 64 samples: 535 in one pass of 64,
// 311 in two of 32). A bound measured with other passes serves a plan only through the measured
// passes each of its passes spans, their bounds added.
TEST(DcsPacking, ReachOfOtherPassesAddsUpTheMeasuredOnes) {
  Reach r;
  EXPECT_EQ(r.forPasses(64, 64), -1) << "nothing measured";
  r.measured(64, 32, 311);
  EXPECT_EQ(r.forPasses(64, 32), 311);
  EXPECT_EQ(r.forPasses(64, 16), 311) << "inside one measured pass";
  EXPECT_EQ(r.forPasses(64, 64), 622) << "two measured passes";
  EXPECT_EQ(r.forPasses(64, 48), 622) << "[0, 48) spans two";
  EXPECT_EQ(r.forPasses(64, 24), 622) << "[24, 48) spans two";
  r.measured(64, 64, 535);
  EXPECT_EQ(r.forPasses(64, 64), 535) << "measured itself";
  EXPECT_EQ(r.forPasses(64, 48), 535) << "inside the pass of 64";
  r.measured(64, 128, 540);  // a pass past the samples is a pass of all of them
  EXPECT_EQ(r.forPasses(64, 64), 540);
  EXPECT_EQ(Reach::any(9).forPasses(64, 7), 9);
  // The engine at 64 samples, from the two passes of 32 alone: base 32 cannot take 4 digits
  // (622 partial counts), so the plan keeps 2 passes, whatever the base; from the pass of 64
  // (535) the same.
  Reach two;
  two.measured(64, 32, 311);
  PackingPlan p = planPacking(64, 30, 4, 0, two, true);
  EXPECT_EQ(p.passes, 2);
  EXPECT_TRUE(p.holds(p.reach));
  EXPECT_GE(p.reach, two.forPasses(64, p.samplesPerPass));
  EXPECT_EQ(planPacking(64, 30, 4, 0, r, true).passes, 2);
  // The paper's rule from measured passes: the digits hold the partial counts of its passes.
  p = planPacking(64, 0, 4, 0, two, false);
  EXPECT_FALSE(p.mayCarry());
  EXPECT_GE(std::int64_t(p.counters.base) - 1, two.forPasses(64, p.samplesPerPass));
}

// Frame to frame (dcs.cpp's counter passes, here their measured counts): the first frame plans
// from the guess, later ones from what the last pass measured; a pass whose counts do not fit
// is planned again so that no count can pass its digit.
TEST(DcsCounterPlanner, PlansFromTheMeasuredCountsAndAgainWhenTheyDoNotFit) {
  CounterPlanner planner;
  const PlanLimits exact{16, 4, 0, true}, paper{16, 4, 0, false};
  const CountBound wide{4095, Reach::any(4095)};
  PackingPlan first = planner.plan(0, exact, wide);
  EXPECT_EQ(first.counters.base, 4096u);
  EXPECT_FALSE(planner.knows(0));
  // The engine's first frame: partial counts 264, final 29 (with the bias); they fit base 4096.
  EXPECT_FALSE(planner.record(0, exact, first, {264, 29, 0}).has_value());
  PackingPlan later = planner.plan(0, exact, wide);
  EXPECT_EQ(later.counters.base, 32u);
  EXPECT_EQ(later.targets, 1);
  EXPECT_TRUE(later.mayCarry());
  EXPECT_EQ(planner.measured(0).final, 29);
  // A later frame whose counts grew past the digit: rendered again, no count can pass it then.
  std::optional<PackingPlan> again = planner.record(0, exact, later, {264, 31, 12});
  ASSERT_TRUE(again.has_value());
  EXPECT_GE(std::int64_t(again->counters.base) - 1, 264);
  // Partial counts past what the plan keeps exact (497 > 496 for 4 digits of base 32): again.
  again = planner.record(0, exact, later, {497, 29, 0});
  ASSERT_TRUE(again.has_value());
  EXPECT_TRUE(again->holds(497));
  // The paper's rule: partial counts past the digit are a rerun, whatever the final ones.
  PackingPlan narrow = planPacking(16, 30, 4);
  again = planner.record(1, paper, narrow, {40, 20, 0});
  ASSERT_TRUE(again.has_value());
  EXPECT_GE(std::int64_t(again->counters.base) - 1, 40);
  EXPECT_FALSE(planner.record(1, paper, *again, {40, 20, 0}).has_value());
  planner.forget(1);
  EXPECT_FALSE(planner.knows(1));
}

}  // namespace
}  // namespace penumbra::dcs
