#include "techniques/dcs/packing.h"

#include <algorithm>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "core/error.h"

namespace penumbra::dcs {

std::string PackingPlan::describe() const {
  return fmt::format("base {} ({} per channel), {} target{}, {} pass{}", counters.base, counters.digits, targets,
                     targets == 1 ? "" : "s", passes, passes == 1 ? "" : "es");
}

namespace {
constexpr std::int64_t kExact = std::int64_t(1) << 24;  // float's exact integers: |x| < 2^24
}  // namespace

bool exactWhileCounting(std::uint32_t base, int digits, std::int64_t reach) {
  std::int64_t weights = 0, w = 1;  // 1 + B + ... + B^(digits-1)
  for (int d = 0; d < digits; ++d, w *= base) {
    weights += w;
    if (weights >= kExact) return false;
  }
  return reach >= 0 && reach * weights < kExact;
}

bool weightedChecksumExact(int samplesPerPass, std::int64_t reach) {
  const std::int64_t weights = std::int64_t(samplesPerPass) * (samplesPerPass + 1) / 2;
  return reach >= 0 && reach * weights < kExact;
}

bool PackingPlan::holds(std::int64_t measuredReach) const {
  if (!exactWhileCounting(counters.base, counters.digits, measuredReach)) return false;
  return measuredReach <= std::int64_t(counters.base) - 1 || weightedChecksumExact(samplesPerPass, measuredReach);
}

Reach Reach::any(std::int64_t bound) {
  Reach r;
  r.any_ = bound;
  return r;
}

void Reach::measured(int samples, int samplesPerPass, std::int64_t bound) {
  byPassSize_[std::min(samplesPerPass, samples)] = bound;
}

std::int64_t Reach::forPasses(int samples, int samplesPerPass) const {
  if (any_ >= 0) return any_;
  std::int64_t best = -1;
  for (auto [size, bound] : byPassSize_) {
    // The most measured passes [k size, (k + 1) size) one pass of the plan overlaps: their
    // positive updates add up at most (each bound also holds D(c) + bias, counted again).
    int most = 0;
    for (int first = 0; first < samples; first += samplesPerPass) {
      const int last = std::min(first + samplesPerPass, samples) - 1;
      most = std::max(most, last / size - first / size + 1);
    }
    const std::int64_t b = bound * most;
    if (best < 0 || b < best) best = b;
  }
  return best;
}

PackingPlan planPacking(int samples, int maxCount, int maxTargets, int minLayout, const Reach& reach,
                        bool finalCounts) {
  PENUMBRA_CHECK(samples >= 1 && maxTargets >= 1, "planPacking arguments");
  auto make = [&](int layout, int digits) {
    PackingPlan p;
    p.layout = layout;
    p.counters = {kLayouts[layout].base, digits};
    const int perTarget = 4 * digits;
    p.targets = std::min((samples + perTarget - 1) / perTarget, maxTargets);
    p.samplesPerPass = perTarget * p.targets;
    p.passes = (samples + p.samplesPerPass - 1) / p.samplesPerPass;
    p.reach = std::max<std::int64_t>(reach.forPasses(samples, p.samplesPerPass), maxCount);
    return p;
  };
  std::optional<PackingPlan> best;
  for (int i = std::max(0, minLayout); i < kLayoutCount; ++i) {
    if (std::int64_t(kLayouts[i].base) - 1 < maxCount) continue;
    // The most digits a channel can hold here (fewest passes and targets for this base).
    for (int digits = kLayouts[i].digits; digits > 0; --digits) {
      const PackingPlan p = make(i, digits);
      if (!finalCounts && p.mayCarry()) continue;
      if (p.reach < 0 || !p.holds(p.reach)) continue;
      if (!best || std::pair(p.passes, p.targets) < std::pair(best->passes, best->targets)) best = p;
      break;
    }
  }
  // Past every layout: the widest, whose pass measures the bound and is refused (dcs.cpp).
  return best ? *best : make(kLayoutCount - 1, 1);
}

PackingPlan planPacking(int samples, int maxCount, int maxTargets, int minLayout, std::int64_t reach) {
  return reach < 0 ? planPacking(samples, maxCount, maxTargets, minLayout, Reach::any(maxCount), false)
                   : planPacking(samples, maxCount, maxTargets, minLayout,
                                 Reach::any(std::max<std::int64_t>(reach, maxCount)), true);
}

PackingPlan widestPlanAtTheCostOf(int samples, int maxCount, int maxTargets, int minLayout) {
  const PackingPlan cost = planPacking(samples, maxCount, maxTargets, minLayout);
  const int fewestPasses = planPacking(samples, 0, maxTargets, minLayout).passes;
  for (int i = kLayoutCount - 1; i >= 0; --i) {
    PackingPlan p = planPacking(samples, int(kLayouts[i].base - 1), maxTargets, minLayout);
    if (p.targets <= cost.targets && p.passes <= fewestPasses) return p;
  }
  return planPacking(samples, 0, maxTargets, minLayout);
}

}  // namespace penumbra::dcs
