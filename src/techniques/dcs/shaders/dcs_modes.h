// dcs's covered-sample and semi-opaque modes and the transmittance of a counter, the same in its
// C++ (edge_lut.h, opacity.h) and its shaders. Valid in both (shared/shared.h); C++ includes
// it through techniques/dcs/dcs_modes.hpp.
#ifndef PENUMBRA_DCS_MODES_H
#define PENUMBRA_DCS_MODES_H

#include "shared/shared.h"

#define PENUMBRA_DCS_MAX_TARGETS 7      // packed counter targets per pass (+1 checksum = 8 MRT)

// ---- dcs covered-sample modes (src/techniques/dcs/edge_lut.h) -------------------------------
#define PENUMBRA_DCS_COVERAGE_EXACT 0   // per-sample 3D test (common_dcs.glsl dcsCovered)
#define PENUMBRA_DCS_COVERAGE_NAIVE 1   // per-sample 2D test on 8-bit packed positions (paper 7.1)
#define PENUMBRA_DCS_COVERAGE_LUT 2     // sector & line bit fields from the edge LUT (paper 7.3)

// ---- dcs semi-opaque occluders (src/techniques/dcs/opacity.h) ------------------------------
#define PENUMBRA_DCS_OPACITY_OPAQUE 0   // one unit per occluder: visible iff the count is 0
#define PENUMBRA_DCS_OPACITY_SUM 1      // the paper's sum of opacities: T = 1 - Sat(count / Q)
#define PENUMBRA_DCS_OPACITY_PRODUCT 2  // units of -ln T: T = exp(-count * delta), 0 from U on

// Transmittance of a counter holding `count` units (negative counts read as 0); opaqueUnits is
// Q (sum) or U (product), unitLog is delta (product).
PENUMBRA_FN float penumbraDcsTransmittance(float count, int mode, float opaqueUnits, float unitLog) {
  float c = max(count, 0.0f);
  if (mode == PENUMBRA_DCS_OPACITY_SUM) return max(1.0f - c / opaqueUnits, 0.0f);
  if (mode == PENUMBRA_DCS_OPACITY_PRODUCT) return c >= opaqueUnits ? 0.0f : exp(-c * unitLog);
  return c > 0.0f ? 0.0f : 1.0f;
}

#endif
