// Float-base packing of depth-complexity counters (DCS paper 7.3, eq. 7-10). A float counts
// every integer up to 2^24 exactly, so one channel holds `digits` counters in base B with
// B^digits = 2^24: base 256 x 3, 64 x 4, 16 x 6, 8 x 8 (the paper's), plus 4096 x 2 and 2^24 x 1,
// our fallbacks for depth complexities above 255. No GL here.
#pragma once

#include <cstdint>
#include <string>

namespace penumbra::dcs {

struct CounterLayout {
  std::uint32_t base;
  int digits;  // counters per float channel
};

// The layouts from the narrowest base (most counters per channel) to the widest.
inline constexpr CounterLayout kLayouts[] = {{8, 8}, {16, 6}, {64, 4}, {256, 3}, {4096, 2}, {1u << 24, 1}};
inline constexpr int kLayoutCount = 6;

struct PackingPlan {
  int layout = 0;          // index into kLayouts
  CounterLayout counters;  // kLayouts[layout]
  int targets = 1;         // RGBA32F targets per pass
  int passes = 1;          // passes over the wedges to cover all samples
  int samplesPerPass = 0;  // 4 * digits * targets
  std::string describe() const;  // "base 64 (4 per channel), 4 targets, 1 pass"
};

// The narrowest layout whose digits hold `maxCount` (base - 1 >= maxCount) at index >= `minLayout`,
// using at most `maxTargets` targets per pass and as few passes as that layout allows.
PackingPlan planPacking(int samples, int maxCount, int maxTargets, int minLayout = 0);

// The widest layout whose plan needs no more targets than the plan for `maxCount` and no more
// passes than the fewest any layout needs: the counts that can be had without an extra pass. A
// light's first frame, with no bound measured yet, plans for it (dcs.cpp, issue 19 section 3;
// a second pass costs as much as the bound pass this replaces, so it is never guessed).
PackingPlan widestPlanAtTheCostOf(int samples, int maxCount, int maxTargets, int minLayout = 0);

}  // namespace penumbra::dcs
