// Progress of a long run (compare, bench) on stderr: a bar redrawn in place when stderr is a
// terminal, one plain log line per step otherwise (CI logs, pipes).
#pragma once

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

}  // namespace penumbra
