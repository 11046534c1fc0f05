// The benchmark studies, each a function taking its command line and writing its tables to
// `out`: run standalone (penumbra_bench_<study>, bench/bench_main.cpp) or all together by
// `penumbra bench` (src/cli/bench.cpp), which writes bench/results/<machine>/.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

namespace penumbra::bench {

// Speed against error on every shipped scene (bench_speed_error.cpp): compare reports with a
// samples sweep against the converged reference, and the cross-scene headline table.
int speedErrorStudy(int argc, char** argv, std::FILE* out);
// DCS paper studies (bench_dcs.cpp): covered-sample modes, sample counts, shading, interleaving,
// semi-opaque occluders.
int dcsStudies(int argc, char** argv, std::FILE* out);
// VWSS paper tables 1-2, figures 8 and 13, map-resolution convergence (bench_multiview.cpp).
int multiviewStudies(int argc, char** argv, std::FILE* out);
// Sterna's table 1, VSSM against PCSS, VSSM stages, single-map errors (bench_pcss.cpp).
int singleMapStudies(int argc, char** argv, std::FILE* out);
// Per-stage timings of chosen techniques and sample counts (bench_techniques.cpp).
int techniqueTimings(int argc, char** argv, std::FILE* out);

struct Study {
  std::string name;         // "speed-error", "dcs", ...
  std::string description;  // one line
  int (*run)(int, char**, std::FILE*);
  std::vector<std::string> fullArgs;   // `penumbra bench`: added to the study's defaults
  std::vector<std::string> quickArgs;  // `penumbra bench --quick`: smaller sizes, fewer frames
};
// The explicit table of studies, in the order `penumbra bench` runs them.
const std::vector<Study>& studyTable();

}  // namespace penumbra::bench
