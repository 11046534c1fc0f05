// Benchmark (not a test): speed against error on every shipped scene (but the bunny crowd, the
// dcs scale case) and the built-in one, in one run on one machine, as a study file
// (bench/studies/speed-error.json, docs/studies.md) planned, run and merged into DIR: the jobs
// (each technique at each sample count, timed against the same-sample and the converged
// reference: raytrace-converged, 1024 stratified light samples a pixel), each scene's report
// (DIR/report/<scene>/) and the headline: per technique and sample count, the geometric mean over
// the scenes of the median frame time and of the visibility RMSE against the converged
// reference, how often the technique is on a scene's Pareto front, and the plot of those means
// (DIR/report/headline.svg, headline.md, summary.md). A run into a DIR that holds an earlier run of
// the same build and scenes renders only what is missing.
//
//   penumbra_bench_speed_error -o DIR [--study bench/studies/speed-error.json] [--backend egl]
#include <cstdio>
#include <filesystem>
#include <set>

#include <fmt/format.h>

#include "core/error.h"
#include "core/log.h"
#include "studies.h"
#include "study/merge.h"
#include "study/plan.h"
#include "study/run.h"
#include "study/study_file.h"

namespace fs = std::filesystem;

namespace penumbra::bench {

int speedErrorStudy(const SpeedErrorOptions& o, std::FILE* out) {
  try {
    const study::StudySpec spec = study::readStudy(o.study);
    const std::vector<study::Job> jobs = study::planJobs(spec);
    study::writePlan(jobs, spec, o.outDir);
    // The job folders of earlier plans (another build, edited scenes) are not this run's.
    std::set<std::string> planned;
    for (const study::Job& j : jobs) planned.insert(j.id);
    std::size_t pruned = 0;
    fs::create_directories(fs::path(o.outDir) / "jobs");
    for (const auto& e : fs::directory_iterator(fs::path(o.outDir) / "jobs"))
      if (!planned.count(e.path().filename().string().substr(0, 16))) pruned += fs::remove_all(e.path()) > 0;
    std::fprintf(out, "Speed against error: study %s (%s), %zu scenes, %zu jobs%s\n\n", spec.name.c_str(),
                 spec.path.c_str(), spec.scenes.size(), jobs.size(),
                 pruned ? fmt::format(" ({} files of earlier plans removed)", pruned).c_str() : "");
    study::RunOptions r;
    r.dir = o.outDir, r.backend = o.backend;
    const study::RunSummary run = study::runStudy(r);
    std::fprintf(out, "%zu jobs: %zu rendered, %zu already done, %zu failed\n\n", run.selected, run.rendered, run.done,
                 run.failed);
    std::fflush(out);
    const study::MergeSummary merged = study::mergeStudy(o.outDir, out);
    return merged.failed > 0 || merged.missing > 0 ? 1 : 0;
  } catch (const Error& e) {
    std::fprintf(stderr, "penumbra_bench_speed_error: %s\n", e.what());
    return 1;
  }
}

}  // namespace penumbra::bench
