// Writing a comparison run (compare/compare.h) for people and programs: report.json,
// report.csv, table.txt, plot.svg (speed against error with the Pareto front) and index.html,
// a self-contained page (no network, no script libraries: images beside it, the plot inline).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "compare/compare.h"

namespace penumbra {

// Indices of the points on the Pareto front of (time, error), both to be minimised: a point is
// on it when every point at least as fast is less accurate (by more than 0.1%, so that results
// equal up to float rounding count as ties and the faster one wins). Sorted by time.
std::vector<std::size_t> paretoFront(const std::vector<std::pair<double, double>>& timeError);

// The plotted runs: every technique run, plus the same-sample reference when the converged
// reference gives it an error.
std::vector<std::size_t> plottedRuns(const CompareResult& r);

// The speed-against-error plot as a standalone SVG document: x = median total ms per frame,
// y = visibility RMSE (CompareRun::plotError), both logarithmic; one colour and one curve per
// technique (its sweep presets, by time), the Pareto front dashed.
std::string speedErrorSvg(const CompareResult& r);

// The human-readable table (table.txt, also printed by `compare`).
std::string reportTable(const CompareResult& r);

std::string reportCsv(const CompareResult& r);
std::string reportHtml(const CompareResult& r);

// Writes report.json, report.csv, table.txt, plot.svg and index.html into `dir`.
void writeReport(const CompareResult& r, const std::string& dir);

}  // namespace penumbra
