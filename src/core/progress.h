// Progress of a long run (compare, bench) on stderr: a bar redrawn in place when stderr is a
// terminal, one plain log line per step otherwise (CI logs, pipes).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>

namespace penumbra {

class Progress {
 public:
  // `total` steps; `interactive` < 0: decide from isatty(stderr).
  explicit Progress(int total, int interactive = -1);
  ~Progress();
  // Starts step `done + 1` of total, described by `what`.
  void step(const std::string& what);
  // Ends the bar's line (the destructor does it too).
  void finish();
  int total() const { return total_; }

 private:
  int total_, done_ = 0;
  bool bar_, open_ = false;
};

// Progress inside one long pass (the reference's rays, the exact unshadowed integral): quiet for
// its first `after` seconds, then a log line every `every` seconds with the part done and the time
// left at the rate so far. advance() may be called from any thread.
class PassProgress {
 public:
  PassProgress(std::string what, std::int64_t total, std::string unit = "rows", double after = 10.0,
               double every = 10.0);
  void advance(std::int64_t units = 1);
  int reports() const { return reports_; }

 private:
  using Clock = std::chrono::steady_clock;
  std::string what_, unit_;
  std::int64_t total_;
  Clock::time_point start_;
  std::int64_t everyNs_;
  std::atomic<std::int64_t> done_{0}, nextNs_;  // nextNs_: since start_
  std::atomic<int> reports_{0};
};

}  // namespace penumbra
