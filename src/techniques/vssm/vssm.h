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
  bool exactSat = true;   // 15-bit integer depths summed in doubles; false: the fp32 table
  int blockerDiv = 5;     // m x m uniform sub-kernels for the blocker search (the paper's m = 5)
  int shadowDiv = 8;      // n x n uniform sub-kernels for the visibility (when shadowLevels = 0)
  int blockerLevels = 0;  // adaptive quad-tree height for the blocker search (0: uniform)
  int shadowLevels = 3;   // adaptive quad-tree height H for the visibility (the paper's H = 3)
};

// The parameters of a preset, its values their defaults: the map ones (the map size must be a
// power of two: the min-max hierarchy halves it), blocker-div, shadow-div, blocker-levels,
// shadow-levels.
std::vector<ParamSpec> vssmParams(const VssmOptions& preset);
std::unique_ptr<Technique> makeVarianceSoftShadowMapping(const TechniqueArgs& args, VssmOptions preset);

}  // namespace penumbra
