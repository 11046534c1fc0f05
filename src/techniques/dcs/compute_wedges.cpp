#include "techniques/dcs/compute_wedges.h"

#include <algorithm>

#include <fmt/format.h>
#include <glm/glm.hpp>

#include "core/error.h"
#include "techniques/dcs/shaders/dcs_bindings.h"  // NOLINT: shared with GLSL

namespace penumbra::dcs {

namespace {
// src/techniques/dcs/shaders/dcs_solid.glsl DcsSolidPlanes.
struct GpuSolid {
  glm::vec4 plane[5];
  glm::ivec4 meta;
  glm::vec4 side[8];  // DCS_SIDE_PLANES
};
// Solids a dispatch: in one long loop over all of them llvmpipe (Mesa 22.3) stopped a tile after
// about 40 chunks of 256 on the engine (its loop limiter), silently.
constexpr unsigned kSolidsPerDispatch = 1024;
}  // namespace

void PassRange::write(const GpuPass& range) {
  if (!buffer_) buffer_ = gl::Buffer(sizeof(GpuPass), nullptr);
  buffer_.write(&range, sizeof range);
  buffer_.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_DCS_PASS);
}

void ComputeWedges::buildSolids(const gl::Program& prog, const gl::Buffer& edgeIds, std::size_t first,
                                std::size_t edges, std::size_t total) {
  const std::size_t bytes = total * sizeof(GpuSolid);
  if (solids_.size() < bytes) solids_ = gl::Buffer(bytes, nullptr);
  prog.set("bandSolids", unsigned(first));
  prog.set("solidCount", unsigned(edges));
  edgeIds.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_DCS_EDGE_IDS);
  solids_.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_DCS_SOLIDS);
  glDispatchCompute(GLuint((edges + 63) / 64), 1, 1);
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

void ComputeWedges::run(PassRange& pass, GpuPass range, int width, int height, int samplesPerPass,
                        const std::vector<std::size_t>& bands, const std::function<void(std::size_t)>& bindBand,
                        const gl::Texture& counters, const gl::Texture& checksum, const std::string& light) {
  constexpr unsigned kTile = PENUMBRA_DCS_TILE, kChunk = kTile * kTile;
  static_assert(kSolidsPerDispatch % kChunk == 0);
  const unsigned tilesX = (unsigned(width) + kTile - 1) / kTile, tilesY = (unsigned(height) + kTile - 1) / kTile;
  const std::size_t bytes =
      sizeof(std::uint32_t) * (1 + std::size_t(width) * std::size_t(height) * std::size_t(samplesPerPass));
  if (counts_.size() != bytes) counts_ = gl::Buffer(bytes, nullptr);
  counts_.clear();
  solids_.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_DCS_SOLIDS);
  counts_.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_DCS_COUNTS);
  counters.bindImage(PENUMBRA_IMAGE_DCS_COUNTERS, GL_READ_WRITE);
  checksum.bindImage(PENUMBRA_IMAGE_DCS_CHECKSUM, GL_READ_WRITE);
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
  std::size_t total = 0;
  for (std::size_t n : bands) total += n;
  std::uint64_t expected = 0;
  unsigned bandFirst = 0;
  for (std::size_t k = 0; k < bands.size(); bandFirst += unsigned(bands[k]), ++k) {
    bindBand(k);
    const unsigned bandEnd = bandFirst + unsigned(bands[k]);
    for (unsigned first = bandFirst; first < bandEnd; first += kSolidsPerDispatch) {
      const unsigned end = std::min(bandEnd, first + kSolidsPerDispatch);
      range.solidFirst = first, range.solidEnd = end, range.finalDispatch = end == total ? 1 : 0;
      pass.write(range);
      glDispatchCompute(tilesX, tilesY, 1);
      glMemoryBarrier(GL_ALL_BARRIER_BITS);
      expected += std::uint64_t(tilesX) * tilesY * ((end - first + kChunk - 1) / kChunk);
    }
  }
  std::uint32_t done = 0;
  counts_.read(&done, sizeof done);
  if (done != expected)
    throw Error("dcs",
                fmt::format("light '{}': the compute path's tiles completed {} of their {} chunks of wedges (the "
                            "driver cut a shader loop short): the counts would be wrong",
                            light, done, expected));
}

}  // namespace penumbra::dcs
