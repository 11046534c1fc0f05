// The edge LUT of dcs/edge_lut.h on the GPU, as src/techniques/dcs/shaders/common_dcs.glsl reads it: the sector
// table as an RGBA32UI cube-map array and the line table as an RGBA32UI 2D array (one layer per
// sample set; bit fields widened to four words, words beyond EdgeLut::words 0), the packed
// sample positions (paper 7.1) as a storage buffer.
#pragma once

#include <cstddef>
#include <string>

#include "gl/objects.h"
#include "techniques/dcs/edge_lut.h"

namespace penumbra::dcs {

struct GpuEdgeLut {
  gl::Texture sector, line;
  gl::Buffer packed;
  float extent = 0.0f;  // EdgeLut::extent
  std::size_t bytes() const { return sector.bytes() + line.bytes() + packed.size(); }
};

GpuEdgeLut uploadEdgeLut(const EdgeLut& table);

// Refuses (Error naming `who`) an edge LUT of `size` for `sets` sets of `samples` that this GL's
// texture limits or this process's memory cannot hold, before buildEdgeLut spends minutes on it:
// the tables' bit fields, their RGBA32UI widening and, on a software GL, the textures.
void checkEdgeLutFits(const std::string& who, const EdgeLutSize& size, int samples, int sets);

}  // namespace penumbra::dcs
