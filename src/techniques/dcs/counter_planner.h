// Adaptive sampling (DCS 5.3) from frame to frame: the counter packing of each light's next
// counter pass, planned from the counts its previous pass measured, and the check that a pass's
// counts fit the plan it ran with. No GL here: dcs.cpp runs the passes.
//
// The paper's counter base holds the largest value any counter reaches, D(c) + bias + the
// positive updates that cover one of its samples; every counter pass measures exactly that per
// pixel (the checksum target's second channel) and the largest final count (the resolve). With
// exact counts (accurate silhouettes, the exact covered-sample test) the raster path plans for
// the final counts with exact partial sums instead (packing.h), and the resolve checks every
// pixel where a count may have passed its digit. The paper's 2D modes and standard silhouettes
// leave counts below -bias at edge-band pixels by design, which that check cannot tell from a
// carry, and the compute path's bound is the final maximum: they keep the paper's rule. A pass
// whose counts do not fit renders again (never a silently wrong count).
#pragma once

#include <cstdint>
#include <map>
#include <optional>

#include "techniques/dcs/packing.h"

namespace penumbra::dcs {

// What a counter plan must hold (both with the bias): the final counts and the partial counts
// on the way (packing.h).
struct CountBound {
  int final = 0;
  Reach reach;
};

// What a counter pass measured (src/techniques/dcs/shaders/dcs_resolve.frag), with the bias.
struct MeasuredCounts {
  std::int64_t reach = 0;         // largest D(c) + bias + positive updates of a pixel
  std::int64_t maxCount = 0;      // largest final count decoded where no digit was passed
  std::uint32_t carryPixels = 0;  // pixels whose digit sums show a count past its digit
};

// How a light's counters may be packed: its samples, the targets a pass may use, the narrowest
// layout allowed, and whether the plan may hold the final counts only (exact counts on the
// raster path; else the paper's rule: the digits hold the partial counts too).
struct PlanLimits {
  int samples = 1;
  int maxTargets = 1;
  int minLayout = 0;
  bool finalCounts = false;
};

class CounterPlanner {
 public:
  bool knows(int light) const { return measured_.count(light) > 0; }
  // The light's measured counts (knows(light) first).
  const CountBound& measured(int light) const { return measured_.at(light); }
  // The plan for the light's next pass: from its measured counts, else from `guess`.
  PackingPlan plan(int light, const PlanLimits& limits, const CountBound& guess) const;
  // Records what a pass with `plan` measured. Returns the plan to render again with when its
  // counts did not fit (a count past its digit, or partial sums past what the plan keeps
  // exact): final counts up to the measured partial bound, so none can pass its digit.
  std::optional<PackingPlan> record(int light, const PlanLimits& limits, const PackingPlan& plan,
                                    const MeasuredCounts& m);
  void forget(int light) { measured_.erase(light); }
  void clear() { measured_.clear(); }

 private:
  std::map<int, CountBound> measured_;  // light index -> its last pass's counts (+ bias)
};

}  // namespace penumbra::dcs
