// Semi-opaque occluders in depth complexity sampling (DCS paper section 3 "Surface opaqueness",
// 4.4): counters hold integer units, so a surface's opacity is discretised into units that each
// crossing of it adds. Two codings (dcs/shaders/dcs_modes.h penumbraDcsTransmittance decodes them):
//  * Sum (the paper's): a surface of opacity a adds round(a * Q) units, an opaque one Q, and
//    T = 1 - Sat(count / Q). Exact for one layer; several layers add their opacities (two
//    layers of 0.5 give T = 0 where the light gets 0.25 through), as the paper says.
//  * Product (beyond the paper): a surface adds round(-ln(1 - a) / delta) units, so counts add
//    up to -ln of the product of the transmittances: T = exp(-count * delta), and 0 from U
//    units on (an opaque surface adds U). Several layers multiply, as the reference's do.
// Q, delta and U are chosen per scene from its opacities so that every single layer's
// transmittance is within `tolerance` of 1 - a with as few units as possible (fewer units: a
// narrower counter base, more counters per channel). Scenes without semi-opaque surfaces use
// neither (one unit per occluder, T = [count == 0]): no semi-opaque path.
// Surfaces of opacity 0 never occlude (0 units), as in the reference; nor do surfaces within
// `tolerance` of transparent (0 units: their single-layer error is their opacity, at most the
// tolerance), which would otherwise need billions of units (hard case 30). An opaque surface is
// at most kMaxOpaqueUnits units, so that 2^24 / kMaxOpaqueUnits = 16 opaque crossings still fit
// the 2^24 a float counter holds exactly (deeper counts are refused at render time). No GL here.
#pragma once

#include <string>
#include <vector>

namespace penumbra::dcs {

enum class OpacityMode { Sum, Product };

inline constexpr int kMaxOpaqueUnits = 1 << 20;

struct OpacityCoding {
  int mode = 0;                  // PENUMBRA_DCS_OPACITY_* (shaders/dcs_modes.h)
  int opaqueUnits = 1;           // Q (sum) or U (product): the units of an opaque surface
  float unitLog = 0.0f;          // product: delta, -ln of the transmittance of one unit
  std::vector<int> units;        // per input opacity: the units one crossing adds (0: no occluder)
  double maxLayerError = 0.0;    // worst |T(units) - (1 - opacity)| over the inputs
  std::string describe() const;  // "product coding: delta 0.0347, opaque = 200 units, ..."
};

// The coding of surfaces with the given opacities (each in [0, 1]). All in {0, 1}: the opaque
// coding. `tolerance` > 0: the largest single-layer transmittance error wanted.
OpacityCoding planOpacity(const std::vector<float>& opacities, OpacityMode mode, double tolerance);

// The transmittance a count of units decodes to (the C++ side of penumbraDcsTransmittance).
float transmittance(const OpacityCoding& coding, float count);

}  // namespace penumbra::dcs
