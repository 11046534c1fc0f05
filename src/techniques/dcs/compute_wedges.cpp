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
// Solids a dcs_solids.comp dispatch writes (1.75 MiB, a range of the solids buffer).
constexpr std::size_t kSolidsPerBuild = 8192;
// A band's solids start at a multiple of this: 8 x 224 bytes = 7 x 256, a multiple of every
// GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT (at most 256).
constexpr std::size_t kSolidAlignment = 8;
static_assert(kSolidsPerDispatch % kSolidAlignment == 0 && kSolidsPerBuild % kSolidAlignment == 0);
}  // namespace

void PassRange::write(const GpuPass& range) {
  if (!buffer_) buffer_ = gl::Buffer(sizeof(GpuPass), nullptr);
  buffer_.write(&range, sizeof range);
  buffer_.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_DCS_PASS);
}

void ComputeWedges::layoutSolids(const std::vector<std::size_t>& bands) {
  bandStart_.clear();
  bandCount_ = bands;
  std::size_t next = 0;
  for (std::size_t n : bands) {
    bandStart_.push_back(next);
    next += (n + kSolidAlignment - 1) / kSolidAlignment * kSolidAlignment;
  }
  const std::size_t bytes = next * sizeof(GpuSolid);
  if (solids_.size() < bytes) solids_ = gl::Buffer(bytes, nullptr);
}

void ComputeWedges::buildSolids(const gl::Program& prog, const gl::Buffer& edgeIds, std::size_t k) {
  edgeIds.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_DCS_EDGE_IDS);
  for (std::size_t first = 0; first < bandCount_[k]; first += kSolidsPerBuild) {
    const std::size_t n = std::min(kSolidsPerBuild, bandCount_[k] - first);
    prog.set("idFirst", unsigned(first));
    prog.set("solidCount", unsigned(n));
    solids_.bindRange(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_DCS_SOLIDS, (bandStart_[k] + first) * sizeof(GpuSolid),
                      n * sizeof(GpuSolid));
    glDispatchCompute(GLuint((n + 63) / 64), 1, 1);
  }
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

void ComputeWedges::run(PassRange& pass, GpuPass range, int width, int height, int samplesPerPass,
                        const std::function<void(std::size_t)>& bindBand, const gl::Texture& counters,
                        const gl::Texture& checksum, const std::string& light) {
  constexpr unsigned kTile = PENUMBRA_DCS_TILE, kChunk = kTile * kTile;
  static_assert(kSolidsPerDispatch % kChunk == 0);
  const unsigned tilesX = (unsigned(width) + kTile - 1) / kTile, tilesY = (unsigned(height) + kTile - 1) / kTile;
  const std::size_t bytes =
      sizeof(std::uint32_t) * (1 + std::size_t(width) * std::size_t(height) * std::size_t(samplesPerPass));
  if (counts_.size() != bytes) counts_ = gl::Buffer(bytes, nullptr);
  counts_.clear();
  counts_.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_DCS_COUNTS);
  counters.bindImage(PENUMBRA_IMAGE_DCS_COUNTERS, GL_READ_WRITE);
  checksum.bindImage(PENUMBRA_IMAGE_DCS_CHECKSUM, GL_READ_WRITE);
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
  std::uint64_t expected = 0;
  std::size_t last = bandCount_.size();  // the last band with solids: its last dispatch is the pass's final one
  for (std::size_t k = 0; k < bandCount_.size(); ++k)
    if (bandCount_[k] > 0) last = k;
  for (std::size_t k = 0; k < bandCount_.size(); ++k) {
    bindBand(k);
    const unsigned count = unsigned(bandCount_[k]);
    for (unsigned first = 0; first < count; first += kSolidsPerDispatch) {
      // The dispatch's solids bound as their own range: dcs_wedge.comp counts them from 0.
      const unsigned end = std::min(count, first + kSolidsPerDispatch);
      solids_.bindRange(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_DCS_SOLIDS, (bandStart_[k] + first) * sizeof(GpuSolid),
                        (end - first) * sizeof(GpuSolid));
      range.solidFirst = 0, range.solidEnd = end - first, range.finalDispatch = k == last && end == count ? 1 : 0;
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
