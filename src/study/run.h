// Running a study's jobs (docs/studies.md): each job renders into DIR/jobs/<id>/, written under a
// temporary name and renamed into place with its row (row.json) last, so that a job is either
// done (its row and every file the row names exist) or not there at all. A job whose row exists
// is skipped (unless forced); a job takes an exclusive lock (DIR/jobs/<id>.lock) while it works,
// so two processes never render the same job, and a process killed mid-job leaves no row (its
// temporary folder, DIR/jobs/<id>.tmp, is removed by the next run of that job). A technique job reads its
// references' frames from DIR and runs their jobs first when they are not done: jobs run in any
// order, on any machine that sees DIR (Slurm arrays, GNU parallel: bench/cluster/).
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "gl/context.h"
#include "study/plan.h"

namespace penumbra::study {

struct RunOptions {
  std::string dir;                   // the study's folder (DIR/jobs.jsonl)
  std::optional<std::size_t> index;  // one job: its line in jobs.jsonl, from 0
  int shard = 0, shards = 1;         // jobs whose index modulo `shards` is `shard`
  int parallel = 1;                  // processes at once (each job in its own process when > 1)
  bool force = false;                // redo the selected jobs (not the references they read)
  bool retryFailed = false;          // redo the selected jobs whose rows say they failed
  gl::Backend backend = gl::Backend::Egl;
};

struct RunSummary {
  std::size_t selected = 0;
  std::size_t rendered = 0;  // jobs this run rendered (their rows written now)
  std::size_t done = 0;      // jobs whose row was there already
  std::size_t failed = 0;    // selected jobs whose row says failed (now or before)
};

// The row of a job that is done (DIR/jobs/<id>/row.json names this id and every file it lists
// exists), else null.
nlohmann::json finishedRow(const std::string& dir, const Job& job);

// Runs the selected jobs. A job that fails writes a failed row (its error and exit code); the
// others go on. Errors of the run itself (no plan, an index past its end): penumbra::Error.
RunSummary runStudy(const RunOptions& options);

}  // namespace penumbra::study
