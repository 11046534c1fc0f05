#include "techniques/dcs/edge_lut_gpu.h"

#include <vector>

namespace penumbra::dcs {

GpuEdgeLut uploadEdgeLut(const EdgeLut& table) {
  // Bit fields widened to RGBA32UI texels (words beyond `words` are 0).
  auto widen = [&](const std::vector<std::uint32_t>& words) {
    std::vector<std::uint32_t> out(words.size() / std::size_t(table.words) * 4, 0u);
    for (std::size_t t = 0; t < words.size() / std::size_t(table.words); ++t)
      for (int w = 0; w < table.words; ++w) out[t * 4 + std::size_t(w)] = words[t * std::size_t(table.words) + std::size_t(w)];
    return out;
  };
  GpuEdgeLut g;
  g.sector = gl::Texture::makeCubeArray(GL_RGBA32UI, table.size.cube, table.sets);
  g.sector.uploadUint4(widen(table.sector).data());
  g.line = gl::Texture::make2DArray(GL_RGBA32UI, table.size.line, table.size.line, table.sets);
  g.line.uploadUint4(widen(table.line).data());
  g.packed = gl::Buffer(table.packed);
  g.extent = table.extent;
  return g;
}

}  // namespace penumbra::dcs
