// StageTimer: harness stages apart from the technique's total, nested stages counted once, and
// the stage counter (pipeline statistics) paused and resumed with its stage.
#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>
#include <thread>

#include "core/timer.h"
#include "core/parallel.h"
#include "core/progress.h"

#include <sstream>

#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

namespace penumbra {
namespace {

// Counts one fragment invocation per begin/end pair and records the call order.
class FakeCounter final : public StageCounter {
 public:
  void begin() override {
    EXPECT_FALSE(active);
    active = true;
    ++begins;
  }
  PipelineCounts end() override {
    EXPECT_TRUE(active);
    active = false;
    PipelineCounts c;
    c.fragmentInvocations = 1;
    return c;
  }
  bool active = false;
  int begins = 0;
};

void sleepMs(int ms) { std::this_thread::sleep_for(std::chrono::milliseconds(ms)); }

TEST(StageTimer, HarnessStagesStayOutOfTheTotal) {
  StageTimer t;
  t.time("draw", [] { sleepMs(2); });
  t.harness("readback", [] { sleepMs(2); });
  ASSERT_EQ(t.stages().size(), 2u);
  EXPECT_EQ(t.stages()[0].kind, StageKind::Technique);
  EXPECT_EQ(t.stages()[1].kind, StageKind::Harness);
  EXPECT_DOUBLE_EQ(t.total(), t.stages()[0].ms);
  EXPECT_DOUBLE_EQ(t.harnessTotal(), t.stages()[1].ms);
  EXPECT_FALSE(t.stages()[0].counted);  // no counter given
}

TEST(StageTimer, NestedStageIsTakenOutOfTheOuterOne) {
  StageTimer t;
  FakeCounter counter;
  t.setCounter(&counter);
  const auto start = std::chrono::steady_clock::now();
  const int r = t.time("views", [&] {
    sleepMs(3);
    t.harness("readback", [] { sleepMs(20); });
    return 7;
  });
  const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r, 7);
  ASSERT_EQ(t.stages().size(), 2u);
  const StageTime &views = t.stages()[0], &readback = t.stages()[1];
  EXPECT_GE(readback.ms, 20.0);
  EXPECT_GE(views.ms, 3.0);
  // The inner 20 ms count once, in the inner stage: the two stages are disjoint parts of the
  // call, so they sum to at most its wall time, however slow a loaded machine makes the sleeps
  // (counted twice, the sum would pass the wall time by the readback's 20 ms or more).
  EXPECT_LE(views.ms + readback.ms, wall + 0.5);
  // views: started, paused for the readback, resumed: two intervals; the readback one.
  EXPECT_EQ(views.counts.fragmentInvocations, 2u);
  EXPECT_EQ(readback.counts.fragmentInvocations, 1u);
  EXPECT_TRUE(views.counted && readback.counted);
  EXPECT_EQ(counter.begins, 3);
  EXPECT_FALSE(counter.active);
}

TEST(StageTimer, AStageThatThrowsRecordsNothingAndStopsTheCounter) {
  StageTimer t;
  FakeCounter counter;
  t.setCounter(&counter);
  EXPECT_THROW(t.time("bad", []() -> int { throw std::runtime_error("x"); }), std::runtime_error);
  EXPECT_FALSE(counter.active);
  t.time("good", [] {});
  ASSERT_EQ(t.stages().size(), 1u);
  EXPECT_EQ(t.stages()[0].stage, "good");
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

// A long pass says how far it is: nothing before `after`, then one line per interval (the
// reports counted across the workers, the line read from the log), never one per row.
TEST(PassProgress, ReportsALongPassOncePerIntervalFromAnyThread) {
  std::ostringstream log;
  auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(log);
  spdlog::default_logger()->sinks().push_back(sink);
  PassProgress quiet("quiet pass", 100, "rows", 60.0, 1.0);
  parallelRows(
      100, 2, [](int, std::uint64_t&) {}, &quiet);
  EXPECT_EQ(quiet.reports(), 0);
  PassProgress slow("slow pass", 40, "rows", 0.0, 0.02);
  parallelRows(
      40, 2, [](int, std::uint64_t&) { std::this_thread::sleep_for(std::chrono::milliseconds(5)); }, &slow);
  spdlog::default_logger()->sinks().pop_back();
  // 40 rows of 5 ms on 2 threads: ~100 ms, a report due every 20 ms.
  EXPECT_GE(slow.reports(), 2);
  EXPECT_LE(slow.reports(), 12);
  EXPECT_EQ(log.str().find("quiet pass"), std::string::npos);
  EXPECT_NE(log.str().find("slow pass: "), std::string::npos) << log.str();
  EXPECT_NE(log.str().find(" of 40 rows) after "), std::string::npos) << log.str();
}

}  // namespace
}  // namespace penumbra
