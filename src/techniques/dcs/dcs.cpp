// `dcs`: depth complexity sampling (Forest, Barthe, Paulin, EG 2008), sections 4, 5.3, 7.2-7.3.
//
// Per light: (1) the z-fail shadow-volume count from the light centre, D(c), the integration
// constant (techniques/shadow_volume, paper 7.2); (2) the potential silhouette edges, accurate
// (edges that are silhouettes for some point of the light) or standard (from the centre);
// (3) the counter packing (adaptive sampling, 5.3): every counter pass measures a bound on
// D(c) + the positive updates of a pixel and the largest final count, later frames plan from
// what the previous frame measured (exact counts: for the final counts, with exact partial
// sums, dcs/packing.h), a light's first frame plans for the widest base at base 256's cost,
// and every frame checks its own counts after the pass and renders again with a wider base if
// a digit could have overflowed; (4) per pass over a subset of the
// samples: counters initialised to D(c) in every digit, then each edge's wedge rasterised
// (src/techniques/dcs/shaders/dcs_wedge.geom) and its exact per-sample update
// (src/techniques/dcs/shaders/common_dcs.glsl) blended into float-packed counters (eq. 7-10), positive and negative
// updates in one pass (exact in float, see src/techniques/dcs/shaders/dcs_wedge.frag); (5) a resolve that decodes the
// counters into per-sample visibility (count <= 0) and the visibility buffer, and checks each pixel's digit sum against
// a checksum of all updates; where the pixel's bound fits the base a mismatch cannot be an overflow and is reported
// (see below), elsewhere it is a carry and the pass is redone.
//
// The compute path (`path=compute`) replaces step (4)'s rasterised wedges: the solids
// of the selected edges (src/techniques/dcs/shaders/dcs_solids.comp), then per 8x8 tile the edges whose solid
// meets the bounding box of the tile's visible points, evaluated per pixel inside the solid with
// the raster path's update function (src/techniques/dcs/shaders/dcs_wedge.comp). It adds each pixel's counts once,
// so the packing holds the final counts only, and its bound is the true maximum count,
// measured exactly (a count past its digit is seen and rendered again).
//
// Semi-opaque occluders add opacity units instead of 1 (dcs/opacity.h); the covered samples
// come from the exact 3D test or the paper's 2D naive loop or edge LUT (dcs/edge_lut.h).
//
// Divergences from the paper, each for exactness: updates integrate along the path from the
// light centre to each sample in 3D (no projection onto a light plane, no clipping), the sign
// of each update comes from the incident triangles at the pixel rather than from outer/inner
// half-wedges, and each edge has one convex wedge solid instead of two half-wedges (see
// src/techniques/dcs/shaders/dcs_wedge.geom).
#include "techniques/dcs/dcs.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>

#include <fmt/format.h>

#include "core/error.h"
#include "core/log.h"
#include "core/memory.h"
#include "gl/objects.h"
#include "gl/program_cache.h"
#include "pipeline/renderer.h"
#include "techniques/dcs/dcs_modes.hpp"
#include "techniques/dcs/compute_wedges.h"
#include "techniques/dcs/counter_planner.h"
#include "techniques/dcs/edge_lut_gpu.h"
#include "techniques/dcs/gpu_silhouette.h"
#include "techniques/dcs/packing.h"
#include "techniques/dcs/wedge_geometry.h"
#include "techniques/common/shadow_volume/shadow_volume.h"
#include "techniques/dcs/shaders/dcs_bindings.h"  // NOLINT: shared with GLSL

namespace penumbra {
namespace {

struct GpuStatus {
  std::uint32_t overflowPixels = 0, maxCount = 0, negativePixels = 0;
  std::uint32_t boundMax = 0;                 // largest D(c) + bias + positive updates of a pixel (dcs_wedge.frag)
  std::uint32_t firstNegative = 0xffffffffu;  // y * width + x of the first pixel with a negative count
  std::uint32_t carryPixels = 0;              // a digit sum off where a count may pass its digit (dcs_resolve.frag)
};

// Bias of every counter digit (src/techniques/dcs/shaders/dcs_init.frag).
constexpr int kBias = 2;
// The counts the compute path's first frame of a light plans for (base 64 with the bias).
constexpr int kComputeFirstCount = 61;
// The raster path's first frame plans for the widest base costing no more than base 256's plan.
constexpr int kFirstFrameCount = 255;
// The largest count the widest layout (one counter per float channel) holds: float adds
// integers exactly below 2^24 (packing.h).
constexpr std::int64_t kMaxExactCount = std::int64_t(dcs::kLayouts[dcs::kLayoutCount - 1].base) - 1;

// Blending for counters and visibility: every fragment adds.
void additiveBlend() {
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE);
}
// Wedge faces are depth-tested against the visible surface: a fragment survives where the
// surface is behind the face (reversed Z: smaller depth).
void beginWedgeState() {
  additiveBlend();
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glDepthFunc(GL_GEQUAL);
  glEnable(GL_DEPTH_CLAMP);
}
void endWedgeState() {
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_CLAMP);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
}

class DepthComplexitySampling final : public Technique {
 public:
  explicit DepthComplexitySampling(const DcsOptions& o) : options_(o) {
    options_.maxTargets = std::clamp(options_.maxTargets, 1, PENUMBRA_DCS_MAX_TARGETS);
    if (const char* env = std::getenv("PENUMBRA_DCS_PROFILE"))
      options_.profile = options_.profile || std::string(env) == "1";
  }

  void prepare(const Scene& scene, GpuScene& gpu) override {
    std::vector<float> opacities;
    for (auto& m : scene.meshes)
      opacities.push_back(std::clamp(scene.materials[std::size_t(m.material)].opacity, 0.0f, 1.0f));
    coding_ = dcs::planOpacity(opacities, options_.opacity, options_.opacityTolerance);
    if (coding_.mode != PENUMBRA_DCS_OPACITY_OPAQUE) PLOG_INFO("dcs: semi-opaque occluders, {}", coding_.describe());
    for (std::size_t i = 0; i < opacities.size(); ++i)
      if (opacities[i] > 0.0f && coding_.units[i] == 0)
        PLOG_INFO(
            "dcs: mesh '{}' (opacity {:.3g}) never occludes: within the single-layer tolerance {:.3g} of transparent",
            scene.meshes[i].name, opacities[i], options_.opacityTolerance);
    volumes_.setBandBytes(options_.bandBytes);
    volumes_.prepare(scene, gpu, coding_.units, coding_.opaqueUnits);
    // The wedges' growth covers the float epsilon of every evaluation point (shared/numerics.h
    // penumbraSurfaceEpsilon), bounded by that of the scene's largest coordinate: more is only
    // slower (the fragment shader decides exactly), less could miss a pixel at a wedge's border.
    const glm::vec3 extent = scene.extent();
    wedgeMargin_ = 2.0f * shared::penumbraSurfaceEpsilon(extent);
    // All meshes' edges and incident triangles in static buffers, a pair a band (each within one
    // storage block: wedge_geometry.h), edge ids global on the CPU, band-relative on the GPU.
    // Refused before it is built when the table, on the CPU and its copy in the GL (llvmpipe:
    // system memory), cannot fit.
    double edgeCount = 0.0, incidenceCount = 0.0;
    for (const auto& m : volumes_.meshes())
      edgeCount += double(m.topology.edges.size()), incidenceCount += double(m.topology.incidences.size());
    checkMemory("dcs", fmt::format("the edge table of {:.0f} edges", edgeCount),
                2.0 * (edgeCount * sizeof(dcs::GpuEdge) + incidenceCount * sizeof(dcs::GpuIncidence)));
    edges_ = dcs::buildEdgeTable(volumes_.meshes(), storageBandBytes(options_.bandBytes));
    edgeBuffers_.clear();
    incidenceBuffers_.clear();
    for (const dcs::EdgeBand& b : edges_.bands) {
      edgeBuffers_.emplace_back((b.endEdge - b.firstEdge) * sizeof(dcs::GpuEdge), &edges_.edges[b.firstEdge]);
      incidenceBuffers_.emplace_back((b.endIncidence - b.firstIncidence) * sizeof(dcs::GpuIncidence),
                                     edges_.incidences.data() + b.firstIncidence);
    }
    if (edges_.bands.size() > 1)
      PLOG_INFO("dcs: {} edges in {} bands of at most {:.3g} MiB (one storage block each)", edges_.edges.size(),
                edges_.bands.size(), double(storageBandBytes(options_.bandBytes)) / 1048576.0);
    statusBuffer_ = gl::Buffer(sizeof(GpuStatus), nullptr);
    profileImage_ = gl::Texture::make2D(GL_R32UI, 7, 1);
    checksum_ = gl::Texture::make2D(GL_RGBA32F, gpu.width(), gpu.height());
    programs_.clear();
    luts_.clear();
    planner_.clear();
    counters_ = gl::Texture();
    emptyVao_ = gl::VertexArray::create();
  }

  // Per light, five named passes over one LightFrame: the centre count D(c) (placement, path
  // crossings, shadow volumes), the edge selection (potential silhouettes), the counter plan
  // (the bound that sizes the counters), the counter passes (init, wedges, resolve; again with a
  // wider base if the measured bound says a digit could have overflowed) and the bound check.
  void renderVisibility(LightPass& lightPass) override {
    LightFrame f;
    f.light = integrationOrigin(lightPass.light);
    LightPass pass{lightPass.scene,         f.light,
                   lightPass.lightIndex,    lightPass.samples,
                   lightPass.gpu,           lightPass.timer,
                   lightPass.cpuGBuffer,    lightPass.visibility,
                   lightPass.perSample,     lightPass.cpuPerSample,
                   lightPass.cpuVisibility, lightPass.cpuShading};
    // The paper's 2D covered-sample modes need a planar light (and its centre as the origin);
    // others use the exact test.
    f.coverage =
        dcs::edgeLutSupports(f.light) && !stats_.shiftedOrigin ? options_.coverage : PENUMBRA_DCS_COVERAGE_EXACT;
    stats_.coverage = f.coverage;
    f.lut = f.coverage != PENUMBRA_DCS_COVERAGE_EXACT ? &lutFor(pass) : nullptr;
    f.corners = dcs::lightCorners(lightPass.light, f.radius);
    f.radius += glm::length(f.light.position - lightPass.light.position);  // around the origin
    // The eye's largest distance to the near-plane window (src/techniques/dcs/shaders/dcs_wedge.geom), with room.
    const Camera& cam = pass.scene.camera;
    const float tanY = std::tan(glm::radians(0.5f * cam.fovY)),
                aspect = float(pass.gpu.width()) / float(pass.gpu.height());
    f.nearRadius = 2.0f * cam.zNear * std::sqrt(1.0f + tanY * tanY * (1.0f + aspect * aspect));

    centreCount(pass, f);
    selectEdges(pass, f, lightPass.light);
    auto [plan, status] = planAndCount(pass, f);
    checkBound(pass, f, plan, status);
  }

  bool providesPerSample() const override { return true; }

  bool seesAlphaTest() const override { return false; }  // wedges and volumes from the meshes' edges

  std::size_t memoryBytes() const override {
    std::size_t lutBytes = 0;
    for (auto& [hash, l] : luts_) lutBytes += l.bytes();
    std::size_t edgeBytes = 0;
    for (std::size_t b = 0; b < edgeBuffers_.size(); ++b)
      edgeBytes += edgeBuffers_[b].size() + incidenceBuffers_[b].size();
    return volumes_.bytes() + checksum_.bytes() + (counters_ ? counters_.bytes() : 0) + edgeBytes + lutBytes +
           compute_.memoryBytes();
  }

  std::vector<std::pair<std::string, double>> statistics() const override {
    std::vector<std::pair<std::string, double>> out = {{"edges", double(stats_.edges)},
                                                       {"edgeChecksum", double(stats_.edgeChecksum)},
                                                       {"edgeBands", double(edges_.bands.size())},
                                                       {"counterBase", double(stats_.plan.counters.base)},
                                                       {"countersPerChannel", double(stats_.plan.counters.digits)},
                                                       {"targets", double(stats_.plan.targets)},
                                                       {"passes", double(stats_.plan.passes)},
                                                       {"boundMaxCount", double(stats_.boundMaxCount)},
                                                       {"countsMayCarry", stats_.plan.mayCarry() ? 1.0 : 0.0},
                                                       {"reruns", double(stats_.reruns)},
                                                       {"maxCount", double(stats_.maxCount)},
                                                       {"negativeCountPixels", double(stats_.negativePixels)},
                                                       {"inconsistentPixels", double(stats_.inconsistentPixels)},
                                                       {"opacityCoding", double(coding_.mode)},
                                                       {"coverageMode", double(stats_.coverage)},
                                                       {"opaqueUnits", double(coding_.opaqueUnits)},
                                                       {"opacityLayerError", coding_.maxLayerError},
                                                       {"closedMeshesPerTriangle", double(stats_.perTriangleMeshes)},
                                                       {"pathCrossings", double(stats_.pathCrossings)},
                                                       {"shiftedOrigin", stats_.shiftedOrigin ? 1.0 : 0.0},
                                                       {"coplanarTriangles", double(stats_.coplanarTriangles)}};
    if (options_.profile) {
      const Profile& p = stats_.profile;
      for (auto [name, value] : {std::pair{"profileRectangleEdges", p.rectangleEdges},
                                 {"profileWedgeEdges", p.wedgeEdges},
                                 {"profileFragments", p.fragments},
                                 {"profileInPlane", p.inPlane},
                                 {"profileWeighted", p.weighted},
                                 {"profileUpdating", p.updating},
                                 {"profileCandidates", p.candidates}})
        out.emplace_back(name, double(value));
    }
    return out;
  }

 private:
  struct Programs {
    const gl::Program &init, &resolve, &resolvePerSample;
    const gl::Program* wedge;  // the raster path's (src/techniques/dcs/shaders/dcs_wedge.*), else null
    const gl::Program* tiles;  // the compute path's (src/techniques/dcs/shaders/dcs_wedge.comp), else null
  };

  using GpuLut = dcs::GpuEdgeLut;
  // What one light's passes share (renderVisibility).
  struct LightFrame {
    Light light;                                 // the light, its position the integration origin (integrationOrigin)
    int coverage = PENUMBRA_DCS_COVERAGE_EXACT;  // the covered-sample mode for this light
    const GpuLut* lut = nullptr;                 // the edge LUT of the 2D modes
    std::vector<glm::vec3> corners;              // the polytope around the light (lightCorners)
    float radius = 0.0f;                         // its bounding radius around the origin
    float nearRadius = 0.0f;                     // the eye's largest distance to the near-plane window
    ShadowVolumeCounter::Placement placed;
    int maxPathGain = 0;       // the most a sample's path crossings can add to its count
    std::vector<int> edgeIds;  // the selected edges, global ids
    // The selected edges of one band of the edge table (wedge_geometry.h), band-relative ids.
    struct Band {
      std::size_t band = 0;
      std::size_t count = 0;
      gl::Buffer idBuffer;
      gl::VertexArray idVao;
    };
    std::vector<Band> bands;  // bands holding a selected edge, in order
  };

  // The integration origin (hard cases 27-28): the light centre, unless it lies exactly on a
  // mesh edge or vertex (a light centred on a box's edge or corner). There a path from it to
  // a sample starts on the border of the surface, where neither the crossing of one triangle
  // (dcs_init.frag) nor an edge update (a wedge whose plane holds the start) describes the
  // jump; any point of the light can serve as the origin of the integration (DCS 4.2: D(s) =
  // D(x) + the changes from x to s), so a point next to the centre, off every border, does.
  Light integrationOrigin(const Light& light) {
    Light origin = light;
    stats_.shiftedOrigin = false;
    if (origin.shape != LightShape::Point && volumes_.onMeshBorder(glm::dvec3(origin.position))) {
      origin.position = offBorder(light);
      stats_.shiftedOrigin = true;
    }
    return origin;
  }

  // Pass 1, the centre count: D(c), the integration constant (paper 7.2). Hard cases 27-29:
  // the closed meshes the light touches or enters are counted per triangle (every crossing),
  // and the paths from the centre to the samples that pass through a triangle get their jump in
  // the init pass (ShadowVolumeCounter::place).
  void centreCount(LightPass& pass, LightFrame& f) {
    const Light& light = f.light;
    ShadowVolumeCounter::Placement& placed = f.placed;
    pass.timer.time("dcs placement", [&] {
      placed = volumes_.place(glm::dvec3(light.position), &pass.samples.positions, double(f.radius),
                              glm::dvec3(pass.gpu.cameraPosition()));
      useRules(placed.rules);
    });
    stats_.perTriangleMeshes = placed.perTriangleMeshes;
    stats_.coplanarTriangles = placed.coplanarTriangles;
    placed.refuseLightOnAFace("dcs", light.name);
    stats_.pathCrossings = placed.crossings.size();
    f.maxPathGain = 0;
    std::vector<dcs::GpuPathCrossing> gpuCrossings;
    for (std::size_t k = 0; k + 1 < placed.firstCrossing.size(); ++k) {
      int gain = 0;
      for (std::uint32_t j = placed.firstCrossing[k]; j < placed.firstCrossing[k + 1]; ++j) {
        const auto& x = placed.crossings[j];
        const auto& m = volumes_.meshes()[x.mesh];
        gain += m.units;
        gpuCrossings.push_back(
            {dcs::trianglePlane(m.topology.weldedPositions, m.topology.weldedTriangles[x.at.triangle]),
             glm::ivec4(x.at.sideC, x.at.sideS, placed.rules[x.mesh] == geo::VolumeRule::ClosedFrontFaces ? 1 : 0,
                        m.units)});
      }
      f.maxPathGain = std::max(f.maxPathGain, gain);
    }
    if (!gpuCrossings.empty()) {
      pathFirstBuffer_ = gl::Buffer(placed.firstCrossing);
      pathBuffer_ = gl::Buffer(gpuCrossings);
    }
    volumes_.count(pass, placed.rules);  // D(c): stages "silhouettes", "shadow volume"
  }

  // Pass 2, the edge selection: the potential silhouette edges of the (unshifted) light,
  // accurate (a silhouette for some point of the light) or standard (from the centre).
  void selectEdges(LightPass& pass, LightFrame& f, const Light& unshifted) {
    std::vector<int>& edgeIds = f.edgeIds;
    pass.timer.time("dcs edges", [&] {
      geo::LightExtent extent = dcs::extentOf(unshifted);
      if (options_.gpuSilhouettes && options_.silhouettes == SilhouetteMode::Accurate) {
        for (std::size_t b = 0; b < edges_.bands.size(); ++b) {
          const dcs::EdgeBand& band = edges_.bands[b];
          for (int id : dcs::gpuAccurateSilhouette(programs_.get({"dcs_silhouette.comp"}), edgeBuffers_[b],
                                                   incidenceBuffers_[b], band.endEdge - band.firstEdge, extent))
            edgeIds.push_back(id + int(band.firstEdge));
        }
        return;
      }
      const auto& meshes = volumes_.meshes();
      for (std::size_t mi = 0; mi < meshes.size(); ++mi) {
        const auto& m = meshes[mi];
        if (m.units == 0) continue;  // never occludes
        if (options_.silhouettes == SilhouetteMode::Accurate) {
          for (auto e : geo::extractAccurateSilhouette(m.topology, extent, f.placed.rules[mi]))
            edgeIds.push_back(int(edges_.offset[mi] + e));
        } else {
          for (auto& s :
               geo::extractPointSilhouette(m.topology, glm::dvec3(f.light.position), f.placed.rules[mi]).sides)
            edgeIds.push_back(int(edges_.offset[mi] + s.edge));
        }
      }
    });
    stats_.edges = edgeIds.size();
    stats_.reruns = 0;
    stats_.edgeChecksum = 0;
    for (int id : edgeIds) stats_.edgeChecksum += std::uint64_t(id) * 2654435761u % 1000003u;
    // Per band, its selected edges in their order, band-relative.
    std::vector<std::vector<int>> perBand(edges_.bands.size());
    for (int id : edgeIds) {
      const std::size_t b = edges_.bandOf(std::uint32_t(id));
      perBand[b].push_back(id - int(edges_.bands[b].firstEdge));
    }
    f.bands.clear();
    for (std::size_t b = 0; b < perBand.size(); ++b) {
      if (perBand[b].empty()) continue;
      LightFrame::Band& band = f.bands.emplace_back();
      band.band = b;
      band.count = perBand[b].size();
      band.idBuffer = gl::Buffer(perBand[b]);
      band.idVao = gl::VertexArray::create();
      band.idVao.vertexBuffer(band.idBuffer, sizeof(int)).attributeInt(0, 1, 0);
    }
  }

  // The storage blocks of band `b` of the edge table, for the wedge stages that read it.
  void bindEdgeBand(std::size_t b) const {
    edgeBuffers_[b].bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_DCS_EDGES);
    incidenceBuffers_[b].bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_DCS_INCIDENCES);
  }

  // Every selected edge's wedge (src/techniques/dcs/shaders/dcs_wedge.*) with `prog`.
  void drawWedges(const gl::Program& prog, const LightPass& pass, const LightFrame& f) {
    if (f.light.shape == LightShape::Point) return;  // every sample is the centre: D(s) = D(c)
    setWedgeUniforms(prog, pass, f);
    for (const LightFrame::Band& band : f.bands) {  // a draw a band, its edges bound
      bindEdgeBand(band.band);
      band.idVao.bind();
      glDrawArrays(GL_POINTS, 0, GLsizei(band.count));
    }
  }

  // The compute path's wedges (src/techniques/dcs/shaders/dcs_wedge.comp) for one pass's samples, after the init
  // pass: their updates added into the counters and the checksum (compute_wedges.h).
  void computeWedges(const gl::Program& prog, const LightPass& pass, const LightFrame& f, const dcs::PackingPlan& plan,
                     const dcs::GpuPass& range) {
    if (f.light.shape == LightShape::Point || f.edgeIds.empty()) return;
    setWedgeUniforms(prog, pass, f);
    compute_.run(
        passRange_, range, pass.gpu.width(), pass.gpu.height(), plan.samplesPerPass,
        [&](std::size_t k) { bindEdgeBand(f.bands[k].band); }, counters_, checksum_, f.light.name);
  }

  // The compute path's solids of the selected edges (src/techniques/dcs/shaders/dcs_solids.comp), once a light.
  void buildSolids(LightPass& pass, const LightFrame& f) {
    if (f.light.shape == LightShape::Point || f.edgeIds.empty()) return;
    pass.timer.time("dcs solids", [&] {
      const gl::Program& prog = programs_.get(
          {"dcs_solids.comp"}, options_.profile ? std::vector<std::string>{"DCS_PROFILE"} : std::vector<std::string>{});
      setWedgeUniforms(prog, pass, f);
      std::vector<std::size_t> counts;  // the solids of f.bands, in order
      for (const LightFrame::Band& band : f.bands) counts.push_back(band.count);
      compute_.layoutSolids(counts);
      for (std::size_t k = 0; k < f.bands.size(); ++k) {
        bindEdgeBand(f.bands[k].band);
        compute_.buildSolids(prog, f.bands[k].idBuffer, k);
      }
    });
  }

  // What the wedge stages read: the light, its polytope, the camera and the margin.
  void setWedgeUniforms(const gl::Program& prog, const LightPass& pass, const LightFrame& f) {
    const Light& light = f.light;
    prog.use();
    setLightUniforms(prog, light, pass.samples);
    prog.set("clipFromWorld", pass.gpu.clipFromWorld());
    for (std::size_t j = 0; j < f.corners.size(); ++j)
      prog.set(fmt::format("lightCorners[{}]", j).c_str(), f.corners[j]);
    prog.set("lightCornerCount", int(f.corners.size()));
    prog.set("eyePosition", pass.gpu.cameraPosition());
    prog.set("nearRadius", f.nearRadius);
    prog.set("margin", wedgeMargin_);
    prog.set("lightRadius", f.radius);
    if (f.lut) {
      glm::vec2 half = light.shape == LightShape::Rect ? 0.5f * light.size : glm::vec2(light.size.x);
      prog.set("lightAxisU", light.tangent / half.x);
      prog.set("lightAxisV", light.bitangent() / half.y);
      prog.set("lutExtent", f.lut->extent);
      f.lut->sector.bind(PENUMBRA_UNIT_DCS_SECTOR_LUT);
      f.lut->line.bind(PENUMBRA_UNIT_DCS_LINE_LUT);
      f.lut->packed.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_DCS_PACKED);
    }
  }

  // Pass 3, the counter plan (adaptive sampling, 5.3; dcs/counter_planner.h plans a light's
  // later frames from the counts its last pass measured). A light's first frame has none: it
  // plans for the widest base that costs no more targets than base 256 and no extra pass (4096
  // at 16 samples, 64 at 64), and its pass measures the counts for the next (and renders again
  // where they do not fit). Before the counts were planned from earlier frames, a separate bound pass measured them
  // first, rasterising every wedge once more (54-70% of a counter pass; engine 256^2: 2.5 s).
  dcs::CountBound firstFrameGuess(const LightPass& pass, const LightFrame& f) const {
    auto both = [](int count) { return dcs::CountBound{count, dcs::Reach::any(count)}; };
    if (options_.firstFrameBound >= 0) {
      const int final = options_.firstFrameBound + kBias + f.maxPathGain;
      return {final, dcs::Reach::any(std::max(final, options_.firstFrameReach + kBias + f.maxPathGain))};
    }
    // The compute path adds each count once: the packing must hold the final counts only, and
    // its pass measures their maximum exactly (src/techniques/dcs/shaders/dcs_wedge.comp). Its first frame plans
    // for counts up to kComputeFirstCount and renders again, with the base the measured
    // maximum needs, when they go higher.
    if (options_.computePath) return both(kComputeFirstCount + kBias + f.maxPathGain);
    const dcs::PackingPlan wide =
        dcs::widestPlanAtTheCostOf(pass.samples.count, kFirstFrameCount, options_.maxTargets, minLayout());
    return both(int(wide.counters.base - 1));
  }

  // Whether the light's counts are exact (a count below -bias is an error, never a design
  // limit), so that the raster path may plan for the final counts (dcs::PlanLimits).
  bool exactCounts(const LightFrame& f) const {
    return f.coverage == PENUMBRA_DCS_COVERAGE_EXACT && options_.silhouettes == SilhouetteMode::Accurate;
  }
  bool plansFinalCounts(const LightFrame& f) const { return exactCounts(f) && !options_.computePath; }

  // The narrowest layout options_.minBase allows.
  int minLayout() const {
    int layout = 0;
    while (layout + 1 < dcs::kLayoutCount && dcs::kLayouts[layout].base < options_.minBase) ++layout;
    return layout;
  }

  // The light's counter plan and its passes, planned again until the counts fit.
  std::pair<dcs::PackingPlan, GpuStatus> planAndCount(LightPass& pass, const LightFrame& f) {
    const Light& light = f.light;
    const bool hadBound = planner_.knows(pass.lightIndex);
    const dcs::PlanLimits limits{pass.samples.count, options_.maxTargets, minLayout(), plansFinalCounts(f)};
    dcs::PackingPlan plan = planner_.plan(pass.lightIndex, limits, firstFrameGuess(pass, f));
    GpuStatus status;
    for (int attempt = 0;; ++attempt) {
      status = counterPasses(pass, f, plan);
      if (std::int64_t(status.boundMax) > kMaxExactCount) {
        planner_.forget(pass.lightIndex);
        refuseDepth(light, double(status.boundMax) - kBias);
      }
      const std::optional<dcs::PackingPlan> again =
          planner_.record(pass.lightIndex, limits, plan, {status.boundMax, status.maxCount, status.carryPixels});
      // Adaptive sampling (5.3): say when the scene's depth complexity costs counters or passes
      // (once per light, from its first measured counts, not on every frame that reuses them).
      if (!hadBound && attempt == 0) {
        const dcs::PackingPlan needed = planner_.plan(pass.lightIndex, limits, {});
        if (needed.layout > minLayout() || needed.passes > 1)
          PLOG_INFO("dcs: light '{}': counts up to {} (partial counts up to {}, with the bias {}) need {}", light.name,
                    planner_.measured(pass.lightIndex).final - kBias, status.boundMax - kBias, kBias,
                    needed.describe());
      }
      if (!again) break;
      PENUMBRA_CHECK(attempt < dcs::kLayoutCount, "dcs: no counter base fits");
      if (status.carryPixels > 0)
        PLOG_INFO("dcs: light '{}': {} pixels with counts past their digit in base {}; rendering again", light.name,
                  status.carryPixels, plan.counters.base);
      else
        PLOG_INFO("dcs: light '{}': partial counts up to {} pass what {} holds; rendering again", light.name,
                  status.boundMax - kBias, plan.describe());
      plan = *again;
      pass.visibility.clear(glm::vec4(0.0f));
      ++stats_.reruns;
    }
    return {plan, status};
  }

  // Pass 4, the counter passes: per pass over a subset of the samples, counters initialised to
  // D(c), all edges' updates, resolve (each pass adds its samples' share of eq. 1-2 into the
  // visibility buffer).
  GpuStatus counterPasses(LightPass& pass, const LightFrame& f, const dcs::PackingPlan& plan) {
    const Light& light = f.light;
    const bool hasPathCrossings = !f.placed.crossings.empty();
    const int N = pass.samples.count;
    GpuStatus status;
    statusBuffer_.write(&status, sizeof status);
    statusBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_DCS_STATUS);
    profileImage_.clear(glm::vec4(0.0f));
    profileImage_.bindImage(PENUMBRA_IMAGE_DCS_PROFILE, GL_READ_WRITE);
    const Programs progs = programsFor(plan, f.coverage);
    ensureCounters(plan, pass.gpu);
    if (progs.tiles) buildSolids(pass, f);
    const gl::Program& resolve = pass.perSample ? progs.resolvePerSample : progs.resolve;
    double w = 1.0, sum = 0.0;  // sum of B^d over a channel's digits
    for (int d = 0; d < plan.counters.digits; ++d, w *= plan.counters.base) sum += w;
    for (int pi = 0; pi < plan.passes; ++pi) {
      unsigned first = unsigned(pi * plan.samplesPerPass);
      unsigned count = unsigned(std::min(plan.samplesPerPass, N - int(first)));
      const dcs::GpuPass range{first, count};
      passRange_.write(range);
      pass.timer.time("dcs wedges", [&] {
        counterFbo_.bind();
        glDisable(GL_BLEND);
        glDisable(GL_DEPTH_TEST);
        volumes_.counter().bind(PENUMBRA_UNIT_COUNTER);
        pass.gpu.bindGBuffer();
        progs.init.use();
        progs.init.set("digitSum", float(sum));
        progs.init.set("pathCrossings", hasPathCrossings ? 1 : 0);
        if (hasPathCrossings) {
          setLightUniforms(progs.init, light, pass.samples);
          progs.init.set("eyePosition", pass.gpu.cameraPosition());
          pathFirstBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_DCS_PATH_FIRST);
          pathBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_DCS_PATH);
        }
        emptyVao_.bind();
        glDrawArrays(GL_TRIANGLES, 0, 3);
        if (progs.tiles) {
          computeWedges(*progs.tiles, pass, f, plan, range);
          return;
        }
        beginWedgeState();
        drawWedges(*progs.wedge, pass,
                   f);  // outer and inner updates together (src/techniques/dcs/shaders/dcs_wedge.frag)
        endWedgeState();
      });
      pass.timer.time("resolve", [&] {
        glMemoryBarrier(GL_ALL_BARRIER_BITS);
        counters_.bind(PENUMBRA_UNIT_DCS_COUNTERS);
        checksum_.bind(PENUMBRA_UNIT_DCS_CHECKSUM);
        if (pass.perSample) pass.perSample->bindImage(PENUMBRA_IMAGE_SAMPLE_VIS, GL_WRITE_ONLY);
        resolve.set("counterBase", float(plan.counters.base));
        resolve.set("opaqueUnits", float(coding_.opaqueUnits));
        resolve.set("unitLog", coding_.unitLog);
        gl::Framebuffer fbo({&pass.visibility}, nullptr);
        fbo.bind();
        additiveBlend();
        pass.gpu.bindGBuffer();
        resolve.use();
        setLightUniforms(resolve, light, pass.samples);
        emptyVao_.bind();
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glDisable(GL_BLEND);
        glMemoryBarrier(GL_ALL_BARRIER_BITS);
      });
    }
    statusBuffer_.read(&status, sizeof status);
    if (options_.profile) {
      const std::vector<std::uint32_t> c =
          profileImage_.readUint();  // src/techniques/dcs/shaders/common_dcs.glsl prof*
      stats_.profile = {c[0], c[1], c[2], c[3], c[4], c[5], c[6]};
    }
    return status;
  }

  // Pass 5, the bound check. The bound makes an overflow impossible: every count stays below
  // D(c) + bound <= B - 1 - bias during and after the update. A digit-sum mismatch therefore
  // means a count below -bias: the shadow-volume count and the wedges disagree about a point
  // (an edge-band pixel of a volume side), and the borrow corrupts the pixel's other samples.
  // With accurate silhouettes and the exact covered-sample test that image is wrong where dcs
  // promises the reference's: an error, never a warning. Standard silhouettes (dcs-standard,
  // they miss edges) and the paper's 2D modes (naive, lut) are approximate by design; they
  // report such pixels.
  void checkBound(const LightPass& pass, const LightFrame& f, const dcs::PackingPlan& plan, const GpuStatus& status) {
    const Light& light = f.light;
    stats_.plan = plan;
    stats_.boundMaxCount = status.boundMax >= std::uint32_t(kBias) ? status.boundMax - kBias : 0;
    stats_.maxCount = status.maxCount >= std::uint32_t(kBias) ? status.maxCount - kBias : 0;
    stats_.negativePixels = status.negativePixels;
    stats_.inconsistentPixels = status.overflowPixels;
    std::size_t pixels = std::size_t(pass.gpu.width()) * std::size_t(pass.gpu.height());
    // A count that ends in [-bias, -1] (read as 0) is the same disagreement, caught by the bias
    // before it borrowed: exact dcs has none on any scene (render_dcs_test), so one is an error too.
    const bool exact = exactCounts(f);
    if ((status.overflowPixels > 0 || status.negativePixels > 0) && exact)
      throw Error("dcs",
                  fmt::format("light '{}': {} pixels with inconsistent counts (a counter left its digit) and {} "
                              "with negative counts{}: the shadow-volume count and the wedges disagree, the image "
                              "would be wrong there",
                              light.name, status.overflowPixels, status.negativePixels,
                              status.negativePixels == 0
                                  ? std::string()
                                  : fmt::format(" (the first at pixel {}, {})",
                                                status.firstNegative % std::uint32_t(pass.gpu.width()),
                                                status.firstNegative / std::uint32_t(pass.gpu.width()))));
    if (status.overflowPixels > pixels / 1000)
      PLOG_WARN("dcs: {} pixels with inconsistent counts (shadow-volume count vs wedges at a volume side)",
                status.overflowPixels);
    PLOG_DEBUG("dcs: {} edges, counts up to {} (partial {}), {}, {} inconsistent pixels", stats_.edges, stats_.maxCount,
               stats_.boundMaxCount, plan.describe(), status.overflowPixels);
  }

  // A light whose counts (its depth complexity times the units of a crossing) pass what a float
  // counter holds exactly: refused, never rendered with rounded counts.
  [[noreturn]] void refuseDepth(const Light& light, double count) const {
    throw Error("dcs", fmt::format("light '{}': counts reach {:.0f} units, past the {} a float counter holds exactly "
                                   "(opaque surfaces are {} units each: {})",
                                   light.name, count, kMaxExactCount, coding_.opaqueUnits, coding_.describe()));
  }
  // src/techniques/dcs/shaders/common_dcs.glsl, dcsProfile (texel k: prof* = k).
  struct Profile {
    std::uint32_t rectangleEdges = 0, wedgeEdges = 0, fragments = 0, inPlane = 0, weighted = 0, updating = 0;
    std::uint32_t candidates = 0;  // compute path: (pixel, edge) pairs its tiles kept
  };
  struct Stats {
    Profile profile;
    std::size_t edges = 0;
    std::uint64_t edgeChecksum = 0;  // order-free digest of the edge set (CPU/GPU path test)
    dcs::PackingPlan plan;
    std::uint32_t maxCount = 0, boundMaxCount = 0, negativePixels = 0, inconsistentPixels = 0;
    std::uint32_t reruns = 0;                    // counter passes run again because the previous frame's bound failed
    int coverage = PENUMBRA_DCS_COVERAGE_EXACT;  // the covered-sample mode of the last light
    std::size_t perTriangleMeshes = 0;           // closed meshes the light touches or enters (counted per triangle)
    std::size_t pathCrossings = 0;               // (sample, triangle) pairs: a centre-to-sample path through a triangle
    std::size_t coplanarTriangles = 0;           // triangles in the light's plane (Placement)
    bool shiftedOrigin = false;  // the light centre lies on a mesh edge or vertex: integrated from next to it
  };

  // A point of the light 1% of its size from the centre (well-conditioned volume sides through
  // the edges at the centre), off every mesh edge and vertex.
  glm::vec3 offBorder(const Light& l) const {
    const float size = l.shape == LightShape::Rect ? 0.5f * std::min(l.size.x, l.size.y) : l.size.x;
    const glm::vec3 t = l.tangent, b = l.bitangent(), n = l.normal;
    glm::vec3 x = l.position;
    for (int k = 0; k < 8; ++k) {
      // Directions away from the axes and from each other (golden-angle turns), inside the
      // light: in its plane for rect and disk, any for a sphere.
      const float a = 0.3f + 2.39996f * float(k);
      glm::vec3 d = std::cos(a) * t + std::sin(a) * b;
      if (l.shape == LightShape::Sphere) d = glm::normalize(d + 0.5f * n);
      x = l.position + (0.01f * float(1 + k)) * size * d;
      if (!volumes_.onMeshBorder(glm::dvec3(x))) return x;
    }
    return x;
  }

  // The closed-rule flag of each edge as `rules` says for this light; the edge buffer is
  // written again only when a mesh's rule changes.
  void useRules(const std::vector<geo::VolumeRule>& rules) {
    if (!edges_.useRules(rules)) return;
    for (std::size_t b = 0; b < edges_.bands.size(); ++b) {
      const dcs::EdgeBand& band = edges_.bands[b];
      edgeBuffers_[b].write(&edges_.edges[band.firstEdge], (band.endEdge - band.firstEdge) * sizeof(dcs::GpuEdge));
    }
  }

  Programs programsFor(const dcs::PackingPlan& plan, int coverage) {
    std::vector<std::string> defs = {"DCS_BIAS " + std::to_string(kBias),
                                     "DCS_TARGETS " + std::to_string(plan.targets),
                                     "DIGITS " + std::to_string(plan.counters.digits),
                                     "DCS_BASE " + std::to_string(plan.counters.base),
                                     "DCS_OPACITY " + std::to_string(coding_.mode),
                                     "DCS_COVERAGE " + std::to_string(coverage)};
    if (options_.profile) defs.push_back("DCS_PROFILE");
    if (options_.endPlanes) defs.push_back("DCS_END_PLANES");
    std::vector<std::string> perSample = defs;
    perSample.push_back("PER_SAMPLE_OUT");
    const bool compute = options_.computePath;
    return {programs_.get({"fullscreen.vert", "dcs_init.frag"}, defs),
            programs_.get({"fullscreen.vert", "dcs_resolve.frag"}, defs),
            programs_.get({"fullscreen.vert", "dcs_resolve.frag"}, perSample),
            compute ? nullptr : &programs_.get({"dcs_wedge.vert", "dcs_wedge.geom", "dcs_wedge.frag"}, defs),
            compute ? &programs_.get({"dcs_wedge.comp"}, defs) : nullptr};
  }

  // The edge LUT of the light's sample pattern on the GPU (edge_lut_gpu.h), loaded or built
  // once per pattern.
  const GpuLut& lutFor(const LightPass& pass) {
    const LightSampleSet& s = pass.samples;
    std::vector<glm::vec2> normalised = dcs::normalisedSamples(s);
    std::uint64_t hash = dcs::patternHash(normalised, s.count, s.setCount);
    auto it = luts_.find(hash);
    if (it != luts_.end()) return it->second;
    std::string path = options_.lutFile;
    if (path.empty()) {
      const std::string dir = options_.lutDirectory.empty() ? PENUMBRA_DEFAULT_LUT_DIR : options_.lutDirectory;
      std::string candidate = dir + "/" + dcs::edgeLutFileName(s);
      if (std::filesystem::exists(candidate)) path = candidate;
    }
    dcs::EdgeLut table;
    pass.timer.time("dcs lut", [&] {
      if (!path.empty()) {
        table = dcs::readEdgeLut(path);
        dcs::checkEdgeLutMatches(table, path, normalised, s.count, s.setCount);
        PLOG_INFO("dcs: edge LUT {}", path);
      } else {
        dcs::checkEdgeLutFits("dcs", options_.lutSize, s.count, s.setCount);
        table = dcs::buildEdgeLut(normalised, s.count, s.setCount, options_.lutSize);
        PLOG_INFO("dcs: edge LUT for {} built in memory (`penumbra lut` writes it to luts/)", dcs::edgeLutFileName(s));
      }
    });
    return luts_.emplace(hash, dcs::uploadEdgeLut(table)).first->second;
  }

  // Counter targets (layers of one array texture) plus the checksum, as one MRT framebuffer.
  void ensureCounters(const dcs::PackingPlan& plan, const GpuScene& gpu) {
    if (counters_ && counters_.layers() == plan.targets) return;
    counters_ = gl::Texture::make2DArray(GL_RGBA32F, gpu.width(), gpu.height(), plan.targets);
    std::vector<gl::Framebuffer::Attachment> att;
    for (int t = 0; t < plan.targets; ++t) att.push_back({&counters_, t});
    att.push_back({&checksum_, -1});
    counterFbo_ = gl::Framebuffer(att, &gpu.depth());
  }

  DcsOptions options_;
  dcs::OpacityCoding coding_;
  ShadowVolumeCounter volumes_;
  float wedgeMargin_ = 0.0f;
  std::vector<gl::Buffer> edgeBuffers_, incidenceBuffers_;  // a pair a band of edges_ (wedge_geometry.h)
  gl::Buffer statusBuffer_;
  dcs::PassRange passRange_;  // the pass's sample range (src/techniques/dcs/shaders/common_dcs_pass.glsl)
  gl::Texture profileImage_;
  dcs::EdgeTable edges_;                     // edgeBuffers_'s and incidenceBuffers_'s contents
  gl::Buffer pathFirstBuffer_, pathBuffer_;  // the light's path crossings (src/techniques/dcs/shaders/dcs_init.frag)
  dcs::ComputeWedges compute_;               // the compute path's solids and counts (path=compute)
  gl::Texture checksum_, counters_;
  gl::Framebuffer counterFbo_;
  gl::ProgramCache programs_;             // by shaders and defines (counter layout, coverage, opacity coding)
  std::map<std::uint64_t, GpuLut> luts_;  // by sample-pattern hash
  dcs::CounterPlanner planner_;           // each light's measured counts, the next frame's plan
  gl::VertexArray emptyVao_;
  Stats stats_;
};

}  // namespace

std::unique_ptr<Technique> makeDepthComplexitySampling(const DcsOptions& options) {
  return std::make_unique<DepthComplexitySampling>(options);
}

}  // namespace penumbra
