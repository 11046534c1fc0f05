#include "core/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

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

}  // namespace penumbra
