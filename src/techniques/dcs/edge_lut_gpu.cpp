#include "techniques/dcs/edge_lut_gpu.h"

#include <vector>

#include <fmt/format.h>

#include "core/error.h"
#include "core/memory.h"

namespace penumbra::dcs {

void checkEdgeLutFits(const std::string& who, const EdgeLutSize& size, int samples, int sets) {
  const gl::Limits& gl = gl::limits();
  if ((gl.maxCubeMapSize > 0 && size.cube > gl.maxCubeMapSize) ||
      (gl.maxTextureSize > 0 && size.line > gl.maxTextureSize) ||
      (gl.maxArrayLayers > 0 && 6 * sets > gl.maxArrayLayers))
    throw Error(who, fmt::format("an edge LUT of {} sets with lut-cube {} and lut-line {} exceeds this GL's textures "
                                 "(cube maps of {}, 2D of {}, {} array layers)",
                                 sets, size.cube, size.line, gl.maxCubeMapSize, gl.maxTextureSize, gl.maxArrayLayers));
  const double texels = double(sets) * (6.0 * size.cube * size.cube + double(size.line) * size.line);
  const double words = double((samples + 31) / 32);
  const double bytes = texels * (words * 4.0 + 16.0) + (gl.maxAllocationBytes > 0 ? texels * 16.0 : 0.0);
  checkMemory(who, fmt::format("an edge LUT of {} sets with lut-cube {} and lut-line {}", sets, size.cube, size.line),
              bytes);
}

GpuEdgeLut uploadEdgeLut(const EdgeLut& table) {
  // Bit fields widened to RGBA32UI texels (words beyond `words` are 0).
  auto widen = [&](const std::vector<std::uint32_t>& words) {
    std::vector<std::uint32_t> out(words.size() / std::size_t(table.words) * 4, 0u);
    for (std::size_t t = 0; t < words.size() / std::size_t(table.words); ++t)
      for (int w = 0; w < table.words; ++w)
        out[t * 4 + std::size_t(w)] = words[t * std::size_t(table.words) + std::size_t(w)];
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
