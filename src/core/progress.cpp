#include "core/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <utility>

#include "core/log.h"

namespace penumbra {

Progress::Progress(int total, int interactive)
    : total_(std::max(total, 1)), bar_(interactive < 0 ? ::isatty(STDERR_FILENO) == 1 : interactive == 1) {}

Progress::~Progress() { finish(); }

void Progress::step(const std::string& what) {
  ++done_;
  if (!bar_) {
    PLOG_INFO("[{}/{}] {}", done_, total_, what);
    return;
  }
  constexpr int width = 30;
  int filled = int(double(width) * (done_ - 1) / total_);
  std::string bar(std::size_t(filled), '#');
  bar.resize(width, '.');
  // \r + clear to the end of the line: the bar stays on one line however long `what` was.
  std::fprintf(stderr, "\r\x1b[K[%s] %d/%d %s", bar.c_str(), done_, total_, what.c_str());
  std::fflush(stderr);
  open_ = true;
}

void Progress::finish() {
  if (!open_) return;
  std::fprintf(stderr, "\r\x1b[K");
  std::fflush(stderr);
  open_ = false;
}

PassProgress::PassProgress(std::string what, std::int64_t total, std::string unit, double after, double every)
    : what_(std::move(what)),
      unit_(std::move(unit)),
      total_(std::max<std::int64_t>(total, 1)),
      start_(Clock::now()),
      everyNs_(std::int64_t(every * 1e9)),
      nextNs_(std::int64_t(after * 1e9)) {}

void PassProgress::advance(std::int64_t units) {
  const std::int64_t done = done_ += units;
  const std::int64_t now = std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start_).count();
  std::int64_t due = nextNs_.load();
  // One thread reports per interval: the one that moves the next report's time on.
  if (now < due || !nextNs_.compare_exchange_strong(due, now + everyNs_)) return;
  ++reports_;
  const double seconds = double(now) * 1e-9, part = double(std::min(done, total_)) / double(total_);
  PLOG_INFO("{}: {:.0f}% ({} of {} {}) after {:.0f} s, about {:.0f} s left", what_, 100.0 * part,
            std::min(done, total_), total_, unit_, seconds, part > 0.0 ? seconds * (1.0 - part) / part : 0.0);
}

}  // namespace penumbra
