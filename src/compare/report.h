// Writing a comparison run (compare/compare.h) for people and programs: report.json,
// report.csv, table.txt, plot.svg (speed against error with the Pareto front) and index.html,
// a self-contained page (no network, no script libraries: images beside it, the plot inline).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "compare/compare.h"
#include "compare/plot.h"

namespace penumbra {

// "Which technique when" from a run's measurements, one sentence a line: the Pareto
// front in words (the fastest technique at each error level), each family's best point, and the
// techniques that failed or left pixels unshadowed on this scene. On the visibility axis.
std::vector<std::string> whichTechniqueWhen(const CompareResult& r);

// The human-readable table (table.txt, also printed by `compare`).
std::string reportTable(const CompareResult& r);

std::string reportCsv(const CompareResult& r);
// A CSV field: as is, or quoted (quotes doubled) when it holds a comma, a quote or a newline.
std::string csvField(const std::string& s);
std::string reportHtml(const CompareResult& r);

// Writes report.json, report.csv, table.txt, plot.svg and index.html into `dir`, each whole or
// not at all (core/files.h writeAtomically).
void writeReport(const CompareResult& r, const std::string& dir);
// Removes those files (a previous run's report, which must not present itself beside this run's
// images).
void removeReport(const std::string& dir);

}  // namespace penumbra
