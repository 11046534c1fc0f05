#include "techniques/dcs/packing.h"

#include <algorithm>

#include <fmt/format.h>

#include "core/error.h"

namespace penumbra::dcs {

std::string PackingPlan::describe() const {
  return fmt::format("base {} ({} per channel), {} target{}, {} pass{}", counters.base, counters.digits, targets,
                     targets == 1 ? "" : "s", passes, passes == 1 ? "" : "es");
}

PackingPlan planPacking(int samples, int maxCount, int maxTargets, int minLayout) {
  PENUMBRA_CHECK(samples >= 1 && maxTargets >= 1, "planPacking arguments");
  PackingPlan plan;
  plan.layout = kLayoutCount - 1;
  for (int i = std::max(0, minLayout); i < kLayoutCount; ++i) {
    if (std::int64_t(kLayouts[i].base) - 1 >= maxCount) {
      plan.layout = i;
      break;
    }
  }
  plan.counters = kLayouts[plan.layout];
  int perTarget = 4 * plan.counters.digits;
  int needed = (samples + perTarget - 1) / perTarget;
  plan.targets = std::min(needed, maxTargets);
  plan.samplesPerPass = perTarget * plan.targets;
  plan.passes = (samples + plan.samplesPerPass - 1) / plan.samplesPerPass;
  return plan;
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
