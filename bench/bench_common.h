// Shared by the benchmarks: time a technique's frames on one renderer (warm-up first, then the
// median and spread of each stage; stages timed with glFinish and a steady clock, as GL timer
// queries are not meaningful on llvmpipe).
#pragma once

#include "pipeline/timing.h"
#include "techniques/registry.h"

namespace penumbra::bench {
using penumbra::frameStatistic;
using penumbra::Spread;
using penumbra::spread;
using penumbra::timeFrames;
using penumbra::Timing;
}  // namespace penumbra::bench
