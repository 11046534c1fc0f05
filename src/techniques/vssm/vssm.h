// `vssm`: variance soft shadow mapping (Yang, Dong, Feng, Seidel, Kautz, PG 2010): the PCSS
// framework on a summed-area table of depth moments; the average blocker depth from the
// moments (eq. 2-4 with z_unocc = t), visibility from Chebyshev's bound (eq. 1), and the
// "non-planarity" problem handled by splitting the kernels into sub-kernels (uniform, section
// 5.2). Shaders: vssm_sat.comp, vssm_resolve.frag.
#pragma once

#include <memory>

#include "pipeline/technique.h"

namespace penumbra {

struct VssmOptions {
  bool exactSat = true;  // 15-bit integer depths summed in doubles; false: the fp32 table
  int blockerDiv = 5;    // m x m sub-kernels for the blocker search (the paper's mixed default m = 5)
  int shadowDiv = 8;     // n x n sub-kernels for the visibility (the paper: adaptive, H = 3 -> 8 x 8)
};

// Parameters (besides the map ones): blocker-div, shadow-div.
std::unique_ptr<Technique> makeVarianceSoftShadowMapping(const TechniqueParams& params, VssmOptions options);

}  // namespace penumbra
