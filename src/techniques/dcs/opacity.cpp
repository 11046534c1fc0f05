#include "techniques/dcs/opacity.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"
#include "techniques/dcs/dcs_modes.hpp"

namespace penumbra::dcs {
namespace {

// Units of each opacity, given the units of one step (sum: 1/Q; product: delta). A
// semi-opaque surface gets at least one unit (it must occlude something) unless its opacity is
// within the tolerance of 0: then 0 units (never occludes) is within the single-layer bound,
// and it is what the rounding gives when the unit is coarser than the opacity.
template <class UnitsOf>
std::vector<int> unitsFor(const std::vector<float>& opacities, int opaqueUnits, double tolerance, UnitsOf unitsOf) {
  std::vector<int> u;
  for (float a : opacities) {
    if (a <= 0.0f)
      u.push_back(0);
    else if (a >= 1.0f)
      u.push_back(opaqueUnits);
    else
      u.push_back(std::clamp(unitsOf(double(a)), double(a) <= tolerance ? 0 : 1, opaqueUnits));
  }
  return u;
}

// A surface that needs units: semi-opaque and not within the tolerance of transparent.
bool needsUnits(float a, double tolerance) { return a < 1.0f && double(a) > tolerance; }

double worstError(const OpacityCoding& c, const std::vector<float>& opacities) {
  double worst = 0.0;
  for (std::size_t i = 0; i < opacities.size(); ++i)
    worst = std::max(worst, std::abs(double(transmittance(c, float(c.units[i]))) - (1.0 - double(opacities[i]))));
  return worst;
}

}  // namespace

std::string OpacityCoding::describe() const {
  switch (mode) {
    case PENUMBRA_DCS_OPACITY_SUM:
      return fmt::format("sum coding (paper): opaque = {} units, worst single-layer error {:.2g}", opaqueUnits,
                         maxLayerError);
    case PENUMBRA_DCS_OPACITY_PRODUCT:
      return fmt::format("product coding: a unit is -ln T = {:.4g}, opaque = {} units, worst single-layer error {:.2g}",
                         unitLog, opaqueUnits, maxLayerError);
    default:
      return "opaque occluders: one unit each";
  }
}

OpacityCoding planOpacity(const std::vector<float>& opacities, OpacityMode mode, double tolerance) {
  PENUMBRA_CHECK(tolerance > 0.0, "planOpacity: tolerance must be positive");
  for (float a : opacities) PENUMBRA_CHECK(a >= 0.0f && a <= 1.0f, "planOpacity: opacity outside [0, 1]");
  OpacityCoding c;
  // Surfaces within the tolerance of transparent (1e-7, 3e-9: hard case 30) never occlude
  // (0 units, error = their opacity <= tolerance); coding them would take -ln(tol) / a units
  // for an opaque surface (2.3e9 for 3e-9: past an int and far past the 2^24 a float counter
  // holds exactly).
  bool semi = std::any_of(opacities.begin(), opacities.end(), [&](float a) { return needsUnits(a, tolerance); });
  if (!semi) {
    c.mode = PENUMBRA_DCS_OPACITY_OPAQUE;
    c.units = unitsFor(opacities, 1, tolerance, [](double) { return 0; });
    c.maxLayerError = worstError(c, opacities);
    return c;
  }
  // Candidates from the coarsest up; the first within tolerance wins, else the best seen.
  OpacityCoding best;
  best.maxLayerError = 2.0;
  auto consider = [&](OpacityCoding& cand) {  // by reference: the winner keeps its error
    cand.maxLayerError = worstError(cand, opacities);
    if (cand.maxLayerError < best.maxLayerError - 1e-12) best = cand;
    return cand.maxLayerError <= tolerance;
  };
  if (mode == OpacityMode::Sum) {
    // Q opaque units: a = k / Q exactly when a is a multiple of 1/Q.
    for (int q = 1; q <= 1024; ++q) {
      OpacityCoding cand;
      cand.mode = PENUMBRA_DCS_OPACITY_SUM;
      cand.opaqueUnits = q;
      cand.units = unitsFor(opacities, q, tolerance, [&](double a) { return int(std::lround(a * q)); });
      if (consider(cand)) return cand;
    }
    return best;
  }
  // Product: delta = L_min / k (L = -ln(1 - a), over the surfaces that need units), so the most
  // transparent of them is exactly k units; U is the first count whose transmittance is below
  // the tolerance (decoded as 0). U stays at most kMaxOpaqueUnits: L_min > -ln(1 - tol) keeps
  // k = 1 near -ln(tol) / tol (7100 for 1/1024), and finer k stop there.
  double lmin = 1e300;
  for (float a : opacities)
    if (needsUnits(a, tolerance)) lmin = std::min(lmin, -std::log1p(-double(a)));
  for (int k = 1; k <= 4096; ++k) {
    OpacityCoding cand;
    cand.mode = PENUMBRA_DCS_OPACITY_PRODUCT;
    double delta = lmin / k;
    double opaque = std::ceil(-std::log(tolerance) / delta);
    if (opaque > double(kMaxOpaqueUnits)) {
      if (k > 1) break;
      // Even the coarsest candidate is too fine (a tolerance far below 1/1024): the finest
      // unit within the budget, its error reported.
      opaque = kMaxOpaqueUnits;
      delta = -std::log(tolerance) / opaque;
    }
    cand.unitLog = float(delta);
    cand.opaqueUnits = int(opaque);
    cand.units = unitsFor(opacities, cand.opaqueUnits, tolerance,
                          [&](double a) { return int(std::lround(-std::log1p(-a) / delta)); });
    if (consider(cand)) return cand;
  }
  return best;
}

float transmittance(const OpacityCoding& c, float count) {
  return shared::penumbraDcsTransmittance(count, c.mode, float(c.opaqueUnits), c.unitLog);
}

}  // namespace penumbra::dcs
