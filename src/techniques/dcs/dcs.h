// `dcs`: depth complexity sampling (Forest, Barthe, Paulin, EG 2008): per light sample, the number
// of occluders between the visible point and the sample, exact against ray tracing.
#pragma once

#include <cstdint>
#include <memory>

#include "pipeline/technique.h"
#include "techniques/dcs/dcs_modes.hpp"
#include "techniques/dcs/edge_lut.h"
#include "techniques/dcs/opacity.h"

namespace penumbra {

enum class SilhouetteMode { Standard, Accurate };

struct DcsOptions {
  SilhouetteMode silhouettes = SilhouetteMode::Accurate;
  int maxTargets = 4;           // packed RGBA32F counter targets per pass (paper: 4; up to 7 here)
  std::uint32_t minBase = 8;    // narrowest counter base allowed (dcs::kLayouts)
  bool gpuSilhouettes = false;  // accurate silhouettes by a compute shader instead of the CPU
  // The counter pass's wedges: rasterised (their solids' front faces, src/techniques/dcs/shaders/dcs_wedge.geom) or
  // binned into screen tiles by a compute shader and evaluated per pixel (src/techniques/dcs/shaders/dcs_wedge.comp).
  bool computePath = false;
  // Wedge solids cut by their end cones' planes (src/techniques/dcs/shaders/dcs_wedge.geom, dcsSidePlanes): the raster
  // path draws the tighter solid (the compute path always tests those planes).
  bool endPlanes = true;
  // Count where the wedge pass's fragments go (statistics "profile*"); atomics slow it down.
  // A debugging aid, also switched on by the environment variable PENUMBRA_DCS_PROFILE=1.
  bool profile = false;
  // >= 0: the first frame of a light plans its counters from this bound instead of the widest
  // base at base 256's cost (the after-pass check and re-render still apply; tests use it to
  // force them).
  int firstFrameBound = -1;
  // > firstFrameBound: that first frame plans for final counts up to firstFrameBound whose
  // partial counts reach this (dcs/packing.h), as a later frame of exact counts does; tests force
  // a carry past a digit with it.
  int firstFrameReach = -1;
  // Semi-opaque occluders (dcs/opacity.h): the paper's sum of opacities or the product of
  // transmittances, and the largest single-layer transmittance error the unit coding may make.
  dcs::OpacityMode opacity = dcs::OpacityMode::Product;
  double opacityTolerance = 1.0 / 1024.0;
  // Covered-sample test (PENUMBRA_DCS_COVERAGE_*): exact (3D, per sample), naive (the paper's
  // loop over 8-bit packed positions) or lut (the paper's edge LUT, section 7.3). The 2D modes
  // serve rect and disk lights; other lights use exact.
  int coverage = PENUMBRA_DCS_COVERAGE_EXACT;
  // The edge LUT: this file if set (refused unless built for the light's sample pattern), else
  // <lutDirectory>/edge_lut.h edgeLutFileName() if it exists (lutDirectory empty: the source
  // tree's luts/), else built in memory.
  std::string lutFile, lutDirectory;
  dcs::EdgeLutSize lutSize;
  // The most bytes a band of the edge table and of the shadow-volume count's buffers holds
  // (wedge_geometry.h, shadow_volume.h); 0: the GL's storage-block limit.
  std::size_t bandBytes = 0;
};

// Every field above as a `--param` (dcs.cpp declares them), its default the preset's: the
// table's variants (dcs-standard, dcs-sum, dcs-naive, dcs-lut) are presets.
std::vector<ParamSpec> dcsParams(const DcsOptions& preset);
DcsOptions readDcsOptions(const TechniqueArgs& args);
std::unique_ptr<Technique> makeDepthComplexitySampling(const DcsOptions& options = {});

}  // namespace penumbra
