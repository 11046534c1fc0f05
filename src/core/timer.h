// Per-stage wall-clock timing. On llvmpipe GL timer queries are not meaningful, so GPU stages
// are timed by calling a sync function (glFinish) before reading a steady clock.
//
// A stage is the technique's own work or the harness's (StageKind): reading results back for
// comparisons, uploading a CPU technique's output. total() is the technique's time; the
// harness's stages are kept apart (harnessTotal()). A stage timed inside another is taken out
// of the outer one (each millisecond counts once). Where a StageCounter is given (the GL's
// pipeline statistics, gl/statistics.h), each stage also records the work the GL counted.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace penumbra {

enum class StageKind { Technique, Harness };

// Machine-independent work of a stage (ARB_pipeline_statistics_query), summed over its draws
// and dispatches.
struct PipelineCounts {
  std::uint64_t primitivesSubmitted = 0;  // primitives the draws sent
  std::uint64_t vertexInvocations = 0;
  std::uint64_t geometryInvocations = 0;
  std::uint64_t clippingOutputPrimitives = 0;  // primitives that reached the rasteriser
  std::uint64_t fragmentInvocations = 0;
  std::uint64_t computeInvocations = 0;
  PipelineCounts& operator+=(const PipelineCounts& o) {
    primitivesSubmitted += o.primitivesSubmitted, vertexInvocations += o.vertexInvocations;
    geometryInvocations += o.geometryInvocations, clippingOutputPrimitives += o.clippingOutputPrimitives;
    fragmentInvocations += o.fragmentInvocations, computeInvocations += o.computeInvocations;
    return *this;
  }
  // (name, value) in the order above, for reports.
  std::vector<std::pair<const char*, std::uint64_t>> fields() const {
    return {{"primitives", primitivesSubmitted}, {"vertex", vertexInvocations},
            {"geometry", geometryInvocations},   {"rasterized", clippingOutputPrimitives},
            {"fragment", fragmentInvocations},   {"compute", computeInvocations}};
  }
};

// Counts the work between begin() and end() (gl::PipelineStatistics).
class StageCounter {
 public:
  virtual ~StageCounter() = default;
  virtual void begin() = 0;
  virtual PipelineCounts end() = 0;
};

struct StageTime {
  std::string stage;
  double ms = 0.0;
  StageKind kind = StageKind::Technique;
  bool counted = false;  // counts were recorded (a StageCounter was given)
  PipelineCounts counts;
};

class StageTimer {
 public:
  // `sync` is called before each clock read (glFinish for GPU work; empty for CPU work).
  explicit StageTimer(std::function<void()> sync = {}) : sync_(std::move(sync)) {}

  // Times fn() and adds it under `stage` (stages with the same name accumulate).
  template <class F>
  auto time(const std::string& stage, F&& fn) {
    return timeAs(stage, StageKind::Technique, std::forward<F>(fn));
  }
  // The same for the harness's work (readbacks, uploads for the pipeline): kept out of total().
  template <class F>
  auto harness(const std::string& stage, F&& fn) {
    return timeAs(stage, StageKind::Harness, std::forward<F>(fn));
  }
  void add(const std::string& stage, double ms, StageKind kind = StageKind::Technique) { find(stage, kind).ms += ms; }
  // Counts the work of the stages from now on (null: none). Not owned; clear it before the
  // counter goes away.
  void setCounter(StageCounter* counter) { counter_ = counter; }
  const std::vector<StageTime>& stages() const { return stages_; }
  double total() const { return sum(StageKind::Technique); }
  double harnessTotal() const { return sum(StageKind::Harness); }
  void clear() { stages_.clear(); }

 private:
  struct Open {
    std::string stage;
    StageKind kind;
  };
  template <class F>
  auto timeAs(const std::string& stage, StageKind kind, F&& fn) {
    begin(stage, kind);
    try {
      if constexpr (std::is_void_v<decltype(fn())>) {
        fn();
        end();
      } else {
        auto r = fn();
        end();
        return r;
      }
    } catch (...) {
      abandon();
      throw;
    }
  }
  StageTime& find(const std::string& stage, StageKind kind) {
    for (auto& s : stages_)
      if (s.stage == stage) return s;
    stages_.push_back({stage, 0.0, kind});
    return stages_.back();
  }
  // Ends the innermost open stage's interval: its time (and counts) so far.
  void stop() {
    if (sync_) sync_();
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0_).count();
    StageTime& s = find(open_.back().stage, open_.back().kind);
    s.ms += ms;
    if (counter_) s.counted = true, s.counts += counter_->end();
  }
  void start() {
    if (sync_) sync_();
    if (counter_) counter_->begin();
    t0_ = std::chrono::steady_clock::now();
  }
  void begin(const std::string& stage, StageKind kind) {
    if (!open_.empty()) stop();  // the outer stage pauses
    open_.push_back({stage, kind});
    start();
  }
  void end() {
    stop();
    open_.pop_back();
    if (!open_.empty()) start();  // the outer stage resumes
  }
  void abandon() {  // a stage that threw: nothing recorded, the counter stopped
    if (counter_) counter_->end();
    open_.pop_back();
    if (!open_.empty()) start();
  }
  double sum(StageKind kind) const {
    double t = 0;
    for (auto& s : stages_)
      if (s.kind == kind) t += s.ms;
    return t;
  }
  std::function<void()> sync_;
  StageCounter* counter_ = nullptr;
  std::chrono::steady_clock::time_point t0_;
  std::vector<StageTime> stages_;
  std::vector<Open> open_;
};

}  // namespace penumbra
