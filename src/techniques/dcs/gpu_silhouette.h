// dcs's accurate silhouette on the GPU (`gpu-silhouettes`, src/techniques/dcs/shaders/dcs_silhouette.comp): the
// same edge set as geo::extractAccurateSilhouette, computed over dcs's edge buffers.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/silhouette.h"
#include "gl/objects.h"
#include "gl/program.h"

namespace penumbra::dcs {

// The ids of the `total` edges of `edges` (with their `incidences`, src/techniques/dcs/shaders/common_dcs.glsl)
// that are silhouettes for some point of the light `l`, by `prog` (dcs_silhouette.comp),
// sorted to compare with the CPU path (the order does not matter to the rendering).
std::vector<int> gpuAccurateSilhouette(const gl::Program& prog, const gl::Buffer& edges, const gl::Buffer& incidences,
                                       std::uint32_t total, const geo::LightExtent& l);

}  // namespace penumbra::dcs
