// The compute path of dcs's wedge pass (`path=compute`): the solids of the selected
// edges (src/techniques/dcs/shaders/dcs_solids.comp), then per screen tile the edges whose solid meets the bounding
// box of the tile's visible points, evaluated per pixel inside the solid with the raster path's
// update function (src/techniques/dcs/shaders/dcs_wedge.comp); the counts are added to the initialised counters
// once, at the end of the pass. Also the buffer both paths read a pass's sample range from
// (src/techniques/dcs/shaders/common_dcs_pass.glsl).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "gl/objects.h"
#include "gl/program.h"

namespace penumbra::dcs {

// src/techniques/dcs/shaders/common_dcs_pass.glsl DcsPass: a counter pass's sample range and, for the compute
// path, one dispatch's solids.
struct GpuPass {
  std::uint32_t first = 0, count = 0, solidFirst = 0, solidEnd = 0;
  std::int32_t finalDispatch = 0;
};

// The DcsPass buffer: written and bound (PENUMBRA_SSBO_DCS_PASS) before the draws that read it.
class PassRange {
 public:
  void write(const GpuPass& range);

 private:
  gl::Buffer buffer_;
};

class ComputeWedges {
 public:
  // Room for a light's solids: `bands[k]` selected edges in band k of the edge table
  // (wedge_geometry.h), in order. One buffer, never bound whole: each dispatch binds the range
  // of its solids (a band's start rounded up to 8 solids, 1792 bytes, a multiple of any GL's
  // storage-buffer offset alignment), so no storage block passes the GL's limit.
  void layoutSolids(const std::vector<std::size_t>& bands);
  // The solids of band k's selected edges, whose band-relative ids `edgeIds` holds, with `prog`
  // (dcs_solids.comp, the wedge uniforms set and in use, the band's edges bound).
  void buildSolids(const gl::Program& prog, const gl::Buffer& edgeIds, std::size_t k);
  // One counter pass's updates by the program in use (dcs_wedge.comp, its wedge uniforms set)
  // into `counters` and `checksum`, for a width x height image with `samplesPerPass` samples a
  // pixel and the pass's samples `range`. The solids go band by band (`bindBand(k)` binding the
  // edges they name), in dispatches of a few chunks (llvmpipe cuts a long shader loop short),
  // the running counts in a buffer between them; every tile's completed chunks are checked and a
  // shortfall is an Error naming `light`.
  void run(PassRange& pass, GpuPass range, int width, int height, int samplesPerPass,
           const std::function<void(std::size_t)>& bindBand, const gl::Texture& counters, const gl::Texture& checksum,
           const std::string& light);
  std::size_t memoryBytes() const { return solids_.size() + counts_.size(); }

 private:
  gl::Buffer solids_;  // the selected edges' wedge solids (src/techniques/dcs/shaders/dcs_solid.glsl DcsSolidPlanes)
  std::vector<std::size_t> bandStart_, bandCount_;  // each band's solids in solids_
  gl::Buffer counts_;  // the pass's running counts between dispatches and the completed chunks
};

}  // namespace penumbra::dcs
