#include "techniques/dcs/opacity.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.h"
#include "sampling/shared.hpp"

namespace penumbra::dcs {
namespace {

// Units of each opacity, given the units of one step (sum: 1/Q; product: delta); every
// semi-opaque surface gets at least one unit (it must occlude something).
template <class UnitsOf>
std::vector<int> unitsFor(const std::vector<float>& opacities, int opaqueUnits, UnitsOf unitsOf) {
  std::vector<int> u;
  for (float a : opacities) {
    if (a <= 0.0f) u.push_back(0);
    else if (a >= 1.0f) u.push_back(opaqueUnits);
    else u.push_back(std::clamp(unitsOf(double(a)), 1, opaqueUnits));
  }
  return u;
}

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
    default: return "opaque occluders: one unit each";
  }
}

OpacityCoding planOpacity(const std::vector<float>& opacities, OpacityMode mode, double tolerance) {
  PENUMBRA_CHECK(tolerance > 0.0, "planOpacity: tolerance must be positive");
  for (float a : opacities) PENUMBRA_CHECK(a >= 0.0f && a <= 1.0f, "planOpacity: opacity outside [0, 1]");
  OpacityCoding c;
  bool semi = std::any_of(opacities.begin(), opacities.end(), [](float a) { return a > 0.0f && a < 1.0f; });
  if (!semi) {
    c.mode = PENUMBRA_DCS_OPACITY_OPAQUE;
    c.units = unitsFor(opacities, 1, [](double) { return 1; });
    return c;
  }
  // Candidates from the coarsest up; the first within tolerance wins, else the best seen.
  OpacityCoding best;
  best.maxLayerError = 2.0;
  auto consider = [&](OpacityCoding cand) {
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
      cand.units = unitsFor(opacities, q, [&](double a) { return int(std::lround(a * q)); });
      if (consider(cand)) return cand;
    }
    return best;
  }
  // Product: delta = L_min / k (L = -ln(1 - a)), so the most transparent layer is exactly k
  // units; U is the first count whose transmittance is below the tolerance (decoded as 0).
  double lmin = 1e300;
  for (float a : opacities)
    if (a > 0.0f && a < 1.0f) lmin = std::min(lmin, -std::log1p(-double(a)));
  for (int k = 1; k <= 4096; ++k) {
    OpacityCoding cand;
    cand.mode = PENUMBRA_DCS_OPACITY_PRODUCT;
    double delta = lmin / k;
    cand.unitLog = float(delta);
    cand.opaqueUnits = int(std::ceil(-std::log(tolerance) / delta));
    cand.units = unitsFor(opacities, cand.opaqueUnits, [&](double a) { return int(std::lround(-std::log1p(-a) / delta)); });
    if (consider(cand)) return cand;
  }
  return best;
}

float transmittance(const OpacityCoding& c, float count) {
  return shared::penumbraDcsTransmittance(count, c.mode, float(c.opaqueUnits), c.unitLog);
}

}  // namespace penumbra::dcs
