// Merging a study's job rows (docs/studies.md): DIR/results.jsonl (every row, in plan order),
// DIR/results.csv (one line a job, for pandas and R) and DIR/report/: per scene the report a
// comparison writes (compare/report.h, its images those of the jobs), and across the scenes the
// headline: per technique (with its parameters) and sample count the geometric means over the
// scenes of the frame time, of its ratio to raytrace's and of the visibility error, each with its
// spread over the study's seeds, how often it is on a scene's Pareto front, the plot of those
// means and which technique when; and which jobs are missing or failed. Rows from different
// renderers are never mixed in one report or mean: each renderer has its own report folder.
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

namespace penumbra::study {

struct MergeSummary {
  std::size_t jobs = 0, ok = 0, failed = 0, missing = 0;
  std::vector<std::string> reports;  // the report folders written (one per renderer)
};

// Writes the files above and the headline's table to `out`.
MergeSummary mergeStudy(const std::string& dir, std::FILE* out);

}  // namespace penumbra::study
