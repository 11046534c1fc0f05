// Per-stage wall-clock timing. On llvmpipe GL timer queries are not meaningful, so GPU stages
// are timed by calling a sync function (glFinish) before reading a steady clock.
#pragma once

#include <chrono>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace penumbra {

struct StageTime {
  std::string stage;
  double ms = 0.0;
};

class StageTimer {
 public:
  // `sync` is called before each clock read (glFinish for GPU work; empty for CPU work).
  explicit StageTimer(std::function<void()> sync = {}) : sync_(std::move(sync)) {}

  // Times fn() and adds it under `stage` (stages with the same name accumulate).
  template <class F>
  auto time(const std::string& stage, F&& fn) {
    begin();
    if constexpr (std::is_void_v<decltype(fn())>) {
      fn();
      end(stage);
    } else {
      auto r = fn();
      end(stage);
      return r;
    }
  }
  void begin() {
    if (sync_) sync_();
    t0_ = std::chrono::steady_clock::now();
  }
  void end(const std::string& stage) {
    if (sync_) sync_();
    double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0_).count();
    add(stage, ms);
  }
  void add(const std::string& stage, double ms) {
    for (auto& s : stages_)
      if (s.stage == stage) { s.ms += ms; return; }
    stages_.push_back({stage, ms});
  }
  const std::vector<StageTime>& stages() const { return stages_; }
  double total() const {
    double t = 0;
    for (auto& s : stages_) t += s.ms;
    return t;
  }
  void clear() { stages_.clear(); }

 private:
  std::function<void()> sync_;
  std::chrono::steady_clock::time_point t0_;
  std::vector<StageTime> stages_;
};

}  // namespace penumbra
