#include "techniques/vwss/vwss.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "core/error.h"
#include "core/log.h"
#include "geometry/silhouette.h"
#include "gl/objects.h"
#include "pipeline/renderer.h"
#include "shared/shared.h"  // NOLINT: shared with GLSL
#include "techniques/common/shadow_map/maps.h"
#include "techniques/common/shadow_map/shaders/shadow_map_bindings.h"  // NOLINT: shared with GLSL

namespace penumbra {
namespace {

struct VwssOptions {
  VwssMode mode = VwssMode::Buffered;
  shadow_map::SplatOptions splat;
  int backFaces = -1;   // 0 cull, 1 keep, -1 (default) keep unless culling provably drops nothing
  double scale = 0.0;   // 0: eq. 3
  long passPoints = 0;  // most points one generation pass holds; 0: the GL's storage-block limit
  int maxView = 4096;   // the point view's side at most (the GL's limit caps it too)
};

const char* modeName(VwssMode m) {
  switch (m) {
    case VwssMode::Unbuffered:
      return "vwss-unbuffered";
    case VwssMode::Graphics:
      return "vwss-graphics";
    default:
      return "vwss";
  }
}

class ViewWarpedSoftShadows final : public shadow_map::MultiViewTechnique {
 public:
  ViewWarpedSoftShadows(const shadow_map::MapOptions& m, int pcf, const VwssOptions& o)
      : MultiViewTechnique(modeName(o.mode), m, pcf), o_(o) {}
  bool cullsSeparatedLights() const override { return true; }  // every map rebuilt from the centre's view

  void prepare(const Scene& scene, GpuScene& gpu) override {
    MultiViewTechnique::prepare(scene, gpu);
    nearest_ = {};
    points_ = gl::Buffer();
    capacity_ = 0;
    occluders_.clear();
    if (o_.backFaces >= 0) return;
    for (const auto& m : scene.meshes) {
      if (scene.materials[std::size_t(m.material)].opacity < 1.0f) continue;  // not in the opaque maps
      Occluder o;
      o.topology = geo::buildEdgeTopology(m.mesh);
      double volume = 0.0;  // six times the signed volume: > 0 for a closed mesh wound outwards
      const auto& P = o.topology.weldedPositions;
      for (const auto& t : o.topology.weldedTriangles)
        volume += glm::dot(glm::dvec3(P[t.x]), glm::cross(glm::dvec3(P[t.y]), glm::dvec3(P[t.z])));
      o.closedOutwards = o.topology.closed && volume > 0.0;
      occluders_.push_back(std::move(o));
    }
  }

 protected:
  void renderMaps(LightPass& pass, const shadow_map::MapFrame& frame) override {
    const Light& light = pass.light;
    // Eq. 1-2: back along the axis until the central frustum holds every sample's frustum: at
    // the light's plane it must span the light (rect: max(w, h), disk: the diameter; sphere
    // and point lights: the samples' lateral reach, and behind the rearmost sample).
    float halfExtent = frame.sampleLateral;
    if (light.shape == LightShape::Rect) halfExtent = 0.5f * std::max(light.size.x, light.size.y);
    if (light.shape == LightShape::Disk) halfExtent = light.size.x;
    const float back = std::max(0.0f, -frame.sampleAxialMin);
    distance_ = halfExtent / frame.tanHalf + back;
    const glm::vec3 eye = light.position - distance_ * frame.axis;
    const float centralNear = std::max(distance_ - back, frame.zNear);
    // Eq. 3: raise the resolution by (z_n + d) / z_n, z_n the nearest occluder beyond the light.
    zn_ = nearest_.get(pass.scene, pass.lightIndex, light.position, frame);
    scaleEq3_ = (zn_ + distance_) / zn_;
    double scale = o_.scale > 0.0 ? o_.scale : scaleEq3_;
    GLint maxFb = 0;
    glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &maxFb);
    // Bounded work: eq. 3 grows without bound as the nearest occluder nears the light (an 8 x 8
    // light 0.35 above a floor asked for 28225^2 points; the GL's 16384^2 took 66 s a frame
    // here). The view stops at `max-view` (and the GL's limit); the warning says what it cuts.
    const double wanted = std::ceil(double(frame.size) * scale);
    const int cap = std::min(o_.maxView, int(maxFb));
    capped_ = wanted > double(cap);
    sourceSize_ = capped_ ? cap : int(wanted);
    if (capped_ && !warnedCap_) {
      const double ratio = double(cap) / double(frame.size);  // eq. 3's (z_n + d) / z_n at the cap
      PLOG_WARN(
          "{}: eq. 3 asks for a {:.0f}^2 point-generation view; capped at {} ({}): occluders nearer the light than "
          "{:.3g} are sampled below mvr's rate",
          name(), wanted, cap, cap == o_.maxView ? "the max-view parameter" : "the GL's limit",
          ratio > 1.0 ? double(distance_) / (ratio - 1.0) : double(INFINITY));
      warnedCap_ = true;
    }

    const gl::Texture* maps = nullptr;
    if (o_.mode == VwssMode::Graphics)
      maps = &ensureMaps(GL_DEPTH_COMPONENT32F, frame);
    else
      maps = &ensureMaps(GL_R32UI, frame);
    if (sourceFbo_.id() == 0 || sourceFboSize_ != sourceSize_) {
      sourceFbo_ = gl::Framebuffer::empty(sourceSize_, sourceSize_);
      sourceFboSize_ = sourceSize_;
    }

    keptBackFaces_ = o_.backFaces == 1 || (o_.backFaces < 0 && backFacesNeeded(pass, eye));
    auto generate = [&](const gl::Program& prog) {
      sourceFbo_.bind();
      glDisable(GL_DEPTH_TEST);
      glDisable(GL_BLEND);
      if (keptBackFaces_) {
        glDisable(GL_CULL_FACE);
      } else {
        glEnable(GL_CULL_FACE);
        glFrontFace(GL_CCW);
        glCullFace(GL_BACK);
      }
      prog.use();
      shadow_map::setMapUniforms(prog, frame);
      prog.set("centralEye", eye);
      prog.set("centralNear", centralNear);
      pass.gpu.drawTriangles(1, GpuScene::Occluders::Opaque, prog);
      glDisable(GL_CULL_FACE);
    };

    if (o_.mode == VwssMode::Unbuffered) {
      pass.timer.time(name() + " points+maps", [&] {
        const gl::Program& prog = program({"vwss_points.vert", "vwss_points.frag"}, {"UNBUFFERED"});
        maps->bindImage(PENUMBRA_IMAGE_SHADOW_MAPS, GL_READ_WRITE);
        prog.set("layerCount", frame.layers);
        generate(prog);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
      });
      pointCount_ = 0;
      return;
    }

    // Buffered: points into the buffer, grown and regenerated if it overflowed, then splatted.
    // One storage block holds at most GL_MAX_SHADER_STORAGE_BLOCK_SIZE bytes (llvmpipe 128 MiB:
    // 11.2 M points; eq. 3 can ask for far more for a large light close to an occluder): then
    // the central view is cut into bands of rows (scissor), each generated and splatted on its
    // own, halved until its points fit. The maps are the same (an atomicMax z-buffer does not
    // depend on the order its points arrive in), only the passes are more.
    const gl::Program& pointsProg = program({"vwss_points.vert", "vwss_points.frag"}, {});
    const std::size_t passLimit = passPointLimit();
    regrown_ = 0, bands_ = 0, dispatches_ = 0;
    pointCount_ = 0;
    // A point a source pixel to start with (the buffer grows when overdraw needs more).
    if (capacity_ == 0) capacity_ = std::max<std::size_t>(std::size_t(sourceSize_) * sourceSize_, 1u << 16);
    capacity_ = std::min(capacity_, passLimit);
    std::vector<std::pair<int, int>> todo = {{0, sourceSize_}};  // bands [y0, y1) of source rows
    while (!todo.empty()) {
      const auto [y0, y1] = todo.back();
      todo.pop_back();
      const bool whole = y0 == 0 && y1 == sourceSize_;
      std::size_t count = 0;
      pass.timer.time(name() + " points", [&] {
        for (;;) {
          if (points_.size() < 16 + 12 * capacity_) {
            points_ = gl::Buffer();
            points_ = gl::Buffer(16 + 12 * capacity_, nullptr);
          }
          const std::uint32_t zero[4] = {0, 0, 0, 0};
          points_.write(zero, sizeof(zero));
          points_.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_POINTS);
          pointsProg.set("pointCapacity", unsigned(capacity_));
          if (!whole) {
            glEnable(GL_SCISSOR_TEST);
            glScissor(0, y0, sourceSize_, y1 - y0);
          }
          generate(pointsProg);
          glDisable(GL_SCISSOR_TEST);
          glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
          std::uint32_t n = 0;
          points_.read(&n, sizeof(n));
          count = n;
          if (count <= capacity_ || count > passLimit) break;
          capacity_ = std::min(passLimit, std::size_t(double(count) * 1.25));
          ++regrown_;
        }
      });
      if (count > capacity_) {  // more than one pass can hold: halve the band
        if (y1 - y0 < 2)
          throw Error(name(),
                      fmt::format("one row of the {}^2 point-generation view holds {} points, more than one pass "
                                  "holds ({}, {}); use a smaller scale{}",
                                  sourceSize_, count, passLimit,
                                  passLimit == std::size_t(o_.passPoints) ? "the pass-points parameter"
                                                                          : "the limit of this GL's storage blocks",
                                  passLimit == std::size_t(o_.passPoints) ? " or a larger pass-points" : ""));
        const int mid = y0 + (y1 - y0) / 2;
        todo.push_back({mid, y1});
        todo.push_back({y0, mid});
        continue;
      }
      ++bands_;
      pointCount_ += count;
      pass.timer.time(name() + " depth maps", [&] { splat(pass, frame, *maps, count); });
    }
    if (pointCount_ == 0) checkNoOccluderInView(pass.scene, frame, eye, centralNear);
  }

  // The points in the buffer into the maps: compute splats (Listing 2) or GL_POINTS draws.
  void splat(LightPass&, const shadow_map::MapFrame& frame, const gl::Texture& maps, std::size_t count) {
    points_.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_POINTS);
    if (o_.mode == VwssMode::Graphics) {
      const gl::Program& prog = program({"vwss_points_draw.vert", "depth_only.frag"}, {});
      prog.use();
      shadow_map::setMapUniforms(prog, frame);
      prog.set("pointCapacity", unsigned(capacity_));
      if (layerFbosFor_ != maps.id()) {
        layerFbos_.clear();
        for (int l = 0; l < frame.layers; ++l)
          layerFbos_.emplace_back(std::vector<gl::Framebuffer::Attachment>{}, &maps, l);
        layerFbosFor_ = maps.id();
      }
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_GREATER);
      glDepthMask(GL_TRUE);
      if (!emptyVao_) emptyVao_ = gl::VertexArray::create();
      emptyVao_.bind();
      for (int l = 0; l < frame.layers; ++l) {
        layerFbos_[std::size_t(l)].bind();
        prog.set("layer", l);
        glDrawArrays(GL_POINTS, 0, GLsizei(count));
      }
      glDisable(GL_DEPTH_TEST);
      glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
      dispatches_ += frame.layers;
    } else {
      const gl::Program& prog = program({"shadow_map_reproject.comp"}, {});
      shadow_map::setMapUniforms(prog, frame);
      prog.set("pointCapacity", unsigned(capacity_));
      dispatches_ += shadow_map::splatMaps(prog, maps, count, frame.layers, o_.splat);
    }
  }

  // Points one generation pass may hold: the storage-block limit (a count, 3 floats a point,
  // after the 16-byte header), or the pass-points parameter when smaller.
  std::size_t passPointLimit() const {
    const GLint64 block = gl::limits().maxStorageBlockSize;
    std::size_t limit = block > 16 ? std::size_t(block - 16) / 12 : std::size_t(1) << 24;
    if (o_.passPoints > 0) limit = std::min(limit, std::size_t(o_.passPoints));
    return limit;
  }

  // Self-check: no point at all is an error when an occluder triangle covers a pixel of the
  // central view (shadow_map::opaqueTriangleCoversAPixel): the pass lost its fragments or stores.
  void checkNoOccluderInView(const Scene& scene, const shadow_map::MapFrame& frame, const glm::vec3& eye,
                             float centralNear) const {
    if (shadow_map::opaqueTriangleCoversAPixel(scene, frame, eye, centralNear, sourceSize_, !o_.backFaces))
      throw Error(name(), fmt::format("the point-generation pass produced no point although occluder triangles "
                                      "cover its {}^2 view (the GL ran no fragment or lost its storage writes)",
                                      sourceSize_));
  }

  std::size_t extraBytes() const override { return points_.size(); }

  void addStatistics(std::vector<std::pair<std::string, double>>& out) const override {
    out.emplace_back("points", double(pointCount_));
    out.emplace_back("point buffer bytes", double(points_.size()));
    out.emplace_back("point buffer regrown", double(regrown_));
    out.emplace_back("source resolution", double(sourceSize_));
    out.emplace_back("eq. 3 scale", scaleEq3_);
    out.emplace_back("source resolution capped", capped_ ? 1.0 : 0.0);
    out.emplace_back("eq. 1 distance", distance_);
    out.emplace_back("z_n", zn_);
    out.emplace_back("maps per thread", o_.splat.mapsPerThread);
    out.emplace_back("point passes", double(dispatches_));
    out.emplace_back("back faces kept", keptBackFaces_ ? 1.0 : 0.0);
    out.emplace_back("point bands", double(bands_));
  }

 private:
  struct Occluder {
    geo::EdgeTopology topology;
    bool closedOutwards = false;
  };

  // Hard case 29: may culling back faces (as seen from the central eye) drop a surface that is
  // the nearest occluder of some sample? A culled triangle t (facing away from the eye) is never
  // the first surface a ray from a sample s meets when s lies strictly behind t's plane and
  // outside t's mesh, that mesh closed and wound outwards: the first surface of a closed mesh
  // met from outside faces the ray's origin. So culling is safe when every triangle either
  // faces the eye (or is edge-on to it: it rasterises nothing either way) or has the whole light
  // behind its plane, in a closed outward mesh the light lies entirely outside of (its centre's
  // winding number 0, no path from the centre to a sample through it). Otherwise (a light below
  // an open floor, inside a tube or a box, straddling a face) back faces are kept. In double, as
  // the shadow volumes decide facing (geometry/silhouette.h).
  bool backFacesNeeded(const LightPass& pass, const glm::vec3& eyeF) const {
    const Light& light = pass.light;
    const glm::dvec3 eye(eyeF), centre(light.position);
    geo::LightExtent extent;
    extent.centre = centre;
    extent.normal = light.normal;
    extent.tangent = light.tangent;
    extent.bitangent = light.bitangent();
    double reach = 0.0;
    for (const glm::vec3& x : pass.samples.positions) reach = std::max(reach, glm::length(glm::dvec3(x) - centre));
    // The samples' ball: conservative for every shape (a sample lies in it).
    extent.kind = reach > 0.0 ? geo::LightExtent::Kind::Sphere : geo::LightExtent::Kind::Point;
    extent.radius = reach;
    for (const Occluder& o : occluders_) {
      bool lightOutside = false;
      if (o.closedOutwards) {
        const geo::PointLocation at = geo::locatePoint(o.topology, centre);
        lightOutside = !at.onSurface && at.winding == 0;
        if (lightOutside && reach > 0.0) {
          std::vector<std::uint32_t> near = geo::trianglesNearBall(o.topology, centre, reach);
          std::vector<geo::PathCrossing> crossings;
          for (std::size_t k = 0; k < pass.samples.positions.size() && crossings.empty() && !near.empty(); ++k)
            geo::pathCrossings(o.topology, near, centre, glm::dvec3(pass.samples.positions[k]), crossings);
          lightOutside = crossings.empty();
        }
      }
      const auto& P = o.topology.weldedPositions;
      for (const auto& t : o.topology.weldedTriangles) {
        const glm::dvec3 a(P[t.x]);
        const glm::dvec3 n = glm::cross(glm::dvec3(P[t.y]) - a, glm::dvec3(P[t.z]) - a);
        if (glm::dot(n, eye - a) >= 0.0) continue;                           // drawn (or edge-on)
        if (lightOutside && geo::classifyLight(extent, n, a) < 0) continue;  // never a first hit
        return true;
      }
    }
    return false;
  }

  const gl::Program& program(const std::vector<std::string>& files, const std::vector<std::string>& defs) {
    return programs().get(files, defs);
  }

  VwssOptions o_;
  std::vector<Occluder> occluders_;  // opaque meshes, for the back-face decision (backfaces unset)
  bool keptBackFaces_ = false;
  shadow_map::NearestOccluder nearest_;
  gl::Buffer points_;
  std::size_t capacity_ = 0, pointCount_ = 0;
  int regrown_ = 0, dispatches_ = 0, bands_ = 0;
  gl::Framebuffer sourceFbo_;
  int sourceFboSize_ = 0, sourceSize_ = 0;
  std::vector<gl::Framebuffer> layerFbos_;
  GLuint layerFbosFor_ = 0;
  gl::VertexArray emptyVao_;
  float distance_ = 0.0f, zn_ = 0.0f;
  double scaleEq3_ = 1.0;
  bool capped_ = false, warnedCap_ = false;
};

}  // namespace

std::vector<ParamSpec> vwssParams(VwssMode mode) {
  std::vector<ParamSpec> p = shadow_map::mapParams();
  p.push_back(shadow_map::pcfParam());
  if (mode == VwssMode::Buffered)
    p.push_back(ParamSpec::integer("k", 8, 0, 4096, "maps per compute thread: 1 serial, 0 all (fully parallel)"));
  p.push_back(
      ParamSpec::integer("backfaces", -1, 0, 1,
                         "unset: keep back faces in point generation (VWSS 3.1's option) unless culling provably "
                         "drops no nearest occluder (every back face has the whole light behind its plane and "
                         "belongs to a closed, outward-wound mesh the light is outside; hard case 29); 0 cull, 1 keep")
          .shown("auto"));
  p.push_back(
      ParamSpec::number("scale", 0.0, 0.0, 64.0, "point-generation resolution over the map resolution; 0: eq. 3")
          .shown("eq. 3"));
  p.push_back(ParamSpec::integer(
      "max-view", VwssOptions{}.maxView, 16, 16384,
      "the point-generation view's side at most (and the GL's limit): eq. 3 asks for "
      "(z_n + d) / z_n times the map, unbounded as an occluder nears the light; a capped view warns"));
  if (mode != VwssMode::Unbuffered)
    p.push_back(
        ParamSpec::integer("pass-points", 0, 0, 1 << 30,
                           "most points one point-generation pass holds (0: the GL's limit); more are split into "
                           "bands of the central view (same maps: atomicMax)")
            .shown("GL limit"));
  return p;
}

std::unique_ptr<Technique> makeViewWarpedSoftShadows(const TechniqueArgs& args, VwssMode mode) {
  VwssOptions o;
  o.mode = mode;
  if (mode == VwssMode::Buffered) o.splat.mapsPerThread = args.integer("k");
  o.backFaces = args.integer("backfaces");
  o.scale = args.number("scale");
  o.maxView = args.integer("max-view");
  if (mode != VwssMode::Unbuffered) o.passPoints = args.integer("pass-points");
  return std::make_unique<ViewWarpedSoftShadows>(shadow_map::readMapOptions(args), shadow_map::readPcfTaps(args), o);
}

}  // namespace penumbra
