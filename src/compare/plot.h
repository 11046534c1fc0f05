// The speed-against-error plot: x = median total ms per frame, y = an error
// (ErrorAxis: the visibility RMSE, the shaded image's RMSE or the mean FLIP), both logarithmic.
// Colour by technique family (Okabe-Ito, colour-blind safe), marker shape and shade by variant
// within the family, the legend grouped by family; one curve per technique (its sweep presets,
// by time); the Pareto front dashed. Every point is labelled: a <text> with the technique's name
// beside it, shown by default for the Pareto front and each family's best point where a greedy
// placement finds room without overlapping another label or point (the rest appear on hover or
// with the page's "all labels" toggle, the class "show-all" on the <svg>).
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "compare/compare.h"

namespace penumbra {

// Indices of the points on the Pareto front of (time, error), both to be minimised: a point is
// on it when every point at least as fast is less accurate (by more than 0.1%, so that results
// equal up to float rounding count as ties and the faster one wins). Sorted by time.
std::vector<std::size_t> paretoFront(const std::vector<std::pair<double, double>>& timeError);

// The plotted runs on `axis`: every technique run with a finite time and error, plus the
// same-sample reference when the converged reference gives it an error.
std::vector<std::size_t> plottedRuns(const CompareResult& r, ErrorAxis axis = ErrorAxis::Visibility);

// Errors below this sit on one floor, on the plot and for the front: exact techniques (dcs
// against the same-sample reference: float rounding, ~1e-8) would otherwise stretch the axis over
// decades of nothing, and put the slower of two exact results on the front.
inline constexpr double kExactErrorFloor = 1e-4;

// The runs (indices into r.runs, by time) on the Pareto front of `axis` among plottedRuns, the
// errors floored at kExactErrorFloor: the plot's, the table's and the summary's front.
std::vector<std::size_t> paretoRuns(const CompareResult& r, ErrorAxis axis = ErrorAxis::Visibility);

// A standalone SVG document (also inlined in index.html).
std::string speedErrorSvg(const CompareResult& r, ErrorAxis axis = ErrorAxis::Visibility);

// A line chart of an error against a swept quantity (the light-size study): one line per series,
// coloured by family and shaped by variant as the speed-against-error plot, both axes
// logarithmic (errors below kExactErrorFloor on the floor), the legend grouped by family.
struct ChartSeries {
  std::string name;
  TechniqueFamily family = TechniqueFamily::ExactPerSample;
  std::vector<std::pair<double, double>> points;  // (x, error), x > 0
};
std::string lineChartSvg(const std::string& title, const std::string& xLabel, const std::string& yLabel,
                         const std::vector<ChartSeries>& series);

// Shared with report.cpp: text escaped for HTML and SVG; a run's name with its preset.
std::string escapeMarkup(const std::string& s);
std::string runLabel(const CompareResult& r, const CompareRun& run);

// The axis's error name, e.g. "visibility RMSE vs converged reference".
std::string errorAxisName(const CompareResult& r, ErrorAxis axis);

}  // namespace penumbra
