// Float-base packing of depth-complexity counters (DCS paper 7.3, eq. 7-10). A float counts
// every integer up to 2^24 exactly, so one channel holds `digits` counters in base B with
// B^digits <= 2^24: base 256 x 3, 64 x 4, 16 x 6, 8 x 8 (the paper's), plus 32 x 4 (2^20, for the
// counts of 30-odd that complex scenes reach), 4096 x 2 and 2^24 x 1, our fallbacks
// for depth complexities above 255. No GL here.
//
// The paper sizes the base for the largest value a counter takes while the updates are blended.
// Float adds of integers are exact while every partial sum stays below 2^24, whatever their
// order, so a digit may pass its base for a while (it carries into its neighbour and a later
// negative update borrows it back): the final value decodes to the right counts when each final
// count fits its digit and the partial sums of the channel stay exact (exactWhileCounting).
// A complex scene's partial counts reach ten times its final ones (engine,
// 16 samples: 263 against 29 with the bias), which the paper's rule pays for in base 4096.
// A final count past its digit changes the plain digit sum by -(B - 1) and an index-weighted
// one as well (src/techniques/dcs/shaders/dcs_resolve.frag); dcs.cpp renders again with the paper's rule then.
#pragma once

#include <cstdint>
#include <map>
#include <string>

namespace penumbra::dcs {

struct CounterLayout {
  std::uint32_t base;
  int digits;  // counters per float channel
};

// The layouts from the narrowest base (most counters per channel) to the widest.
// Digits: the most a channel holds.
inline constexpr CounterLayout kLayouts[] = {{8, 8}, {16, 6}, {32, 4}, {64, 4}, {256, 3}, {4096, 2}, {1u << 24, 1}};
inline constexpr int kLayoutCount = 7;

// Whether `digits` counters in `base` whose partial values stay in [-reach, reach] keep every
// partial sum of their channel exact: reach * (1 + B + ... + B^(digits-1)) < 2^24.
bool exactWhileCounting(std::uint32_t base, int digits, std::int64_t reach);

// Whether the index-weighted digit sum (weights 1..samplesPerPass, src/techniques/dcs/shaders/dcs_resolve.frag)
// stays exact for partial counts up to `reach`: it is checked where a count may pass its digit.
bool weightedChecksumExact(int samplesPerPass, std::int64_t reach);

struct PackingPlan {
  int layout = 0;          // index into kLayouts
  CounterLayout counters;  // kLayouts[layout].base, digits up to kLayouts[layout].digits
  int targets = 1;         // RGBA32F targets per pass
  int passes = 1;          // passes over the wedges to cover all samples
  int samplesPerPass = 0;  // 4 * digits * targets
  std::int64_t reach = 0;  // the largest partial count the plan keeps exact
  // A partial count may pass its digit (reach > base - 1): the final counts are checked.
  bool mayCarry() const { return reach > std::int64_t(counters.base) - 1; }
  // Whether the plan stays exact for partial counts up to `reach` (measured after a pass).
  bool holds(std::int64_t measuredReach) const;
  std::string describe() const;  // "base 64 (4 per channel), 4 targets, 1 pass"
};

// Bounds on the partial counts of a pixel (D(c) + bias + its positive updates on the pass's
// samples), which grow with the samples a pass holds: measured per pass size (a pass of the
// plan may span several measured ones, each adding its bound), or one bound for passes of any
// size (a guess, or the first-bound parameter).
class Reach {
 public:
  static Reach any(std::int64_t bound);
  // A counter pass over passes of `samplesPerPass` of the `samples` measured `bound`.
  void measured(int samples, int samplesPerPass, std::int64_t bound);
  // A bound for the passes of a plan with `samplesPerPass` (-1: nothing measured).
  std::int64_t forPasses(int samples, int samplesPerPass) const;

 private:
  std::int64_t any_ = -1;
  std::map<int, std::int64_t> byPassSize_;  // samples a pass (at most `samples`) -> bound
};

// The cheapest plan (fewest passes, then fewest targets, then the narrowest base) over the
// layouts at index >= `minLayout` whose digits hold a final count of `maxCount`
// (base - 1 >= maxCount), using at most `maxTargets` targets per pass. finalCounts: the
// channels only stay exact for the partial counts (`reach` for the plan's passes); else the
// digits hold them too (the paper's rule).
PackingPlan planPacking(int samples, int maxCount, int maxTargets, int minLayout, const Reach& reach, bool finalCounts);
// The same with one bound for passes of any size: `reach` >= 0 plans for the final counts,
// -1 by the paper's rule for maxCount.
PackingPlan planPacking(int samples, int maxCount, int maxTargets, int minLayout = 0, std::int64_t reach = -1);

// The widest layout whose plan needs no more targets than the plan for `maxCount` and no more
// passes than the fewest any layout needs: the counts that can be had without an extra pass. A
// light's first frame, with no bound measured yet, plans for it (dcs.cpp;
// a second pass costs as much as the bound pass this replaces, so it is never guessed).
PackingPlan widestPlanAtTheCostOf(int samples, int maxCount, int maxTargets, int minLayout = 0);

}  // namespace penumbra::dcs
