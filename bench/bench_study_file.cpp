// Benchmark (not a test): a study file (docs/studies.md) planned, run and merged into DIR in one
// process on one machine: the jobs (each technique at each configuration, timed against the
// same-sample reference and, where the study asks, the converged one), each scene's report
// (DIR/report/<scene>/), the headline across the scenes (DIR/report/headline.md, headline.svg,
// summary.md), the per-stage tables (stages.md) and, for a study with several light scales, the
// error against light size (light-size.md). A run into a DIR that holds an earlier run of the
// same build and scenes renders only what is missing.
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

int studyFile(const StudyFileOptions& o, std::FILE* out) {
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
    std::fprintf(out, "Study %s (%s): %zu scenes, %zu jobs%s\n\n", spec.name.c_str(), spec.path.c_str(),
                 spec.allScenes().size(), jobs.size(),
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
    std::fprintf(stderr, "penumbra bench: %s\n", e.what());
    return 1;
  }
}

}  // namespace penumbra::bench
