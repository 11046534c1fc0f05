#include "techniques/dcs/counter_planner.h"

#include <algorithm>

namespace penumbra::dcs {

PackingPlan CounterPlanner::plan(int light, const PlanLimits& limits, const CountBound& guess) const {
  auto known = measured_.find(light);
  const CountBound& b = known != measured_.end() ? known->second : guess;
  return planPacking(limits.samples, b.final, limits.maxTargets, limits.minLayout, b.reach, limits.finalCounts);
}

std::optional<PackingPlan> CounterPlanner::record(int light, const PlanLimits& limits, const PackingPlan& plan,
                                                  const MeasuredCounts& m) {
  // The largest final count, where no count passed its digit (else the partial bound holds it).
  const int reach = int(m.reach);
  const int final = m.carryPixels == 0 ? int(std::min(m.maxCount, m.reach)) : reach;
  // Partial counts grow with the samples a pass holds: kept per pass size (a later plan with
  // other passes adds up the ones it spans).
  CountBound& b = measured_[light];
  b.final = final;
  b.reach.measured(limits.samples, plan.samplesPerPass, reach);
  const bool fits = limits.finalCounts ? plan.holds(reach) : std::int64_t(plan.counters.base) - 1 >= reach;
  if (m.carryPixels == 0 && fits) return std::nullopt;
  return planPacking(limits.samples, reach, limits.maxTargets, limits.minLayout, b.reach, limits.finalCounts);
}

}  // namespace penumbra::dcs
