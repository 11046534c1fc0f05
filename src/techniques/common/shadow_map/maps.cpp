#include "techniques/common/shadow_map/maps.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>

#include <fmt/format.h>

#include "core/error.h"
#include "gl/context.h"
#include "pipeline/renderer.h"
#include "shared/shared.hpp"
#include "techniques/common/shadow_map/shaders/shadow_map_bindings.h"  // NOLINT: shared with GLSL

namespace penumbra::shadow_map {

std::vector<ParamSpec> mapParams() {
  const MapOptions o;
  return {
      ParamSpec::integer("map", o.size, 16, 16384, "depth-map resolution (square)"),
      ParamSpec::number(
          "bias", o.biasConstant, -1.0, 1e30,
          "constant depth bias, world units along the view axis; < 0: per point (eps: `shared/numerics.h` "
          "penumbraSurfaceEpsilon, relative to the positions' float magnitude)")
          .shown("per point: 4 x (eps(p) + eps(sample))"),
      ParamSpec::number(
          "slope-bias", o.biasSlope, 0.0, 100.0,
          "slope margin on top of the receiver-plane depth, in texels of the receiver plane's depth slope"),
      ParamSpec::number("max-angle", o.maxHalfAngle, 1.0, 89.0,
                        "widest frustum half-angle (degrees); receivers beyond it are left unshadowed, and said so per "
                        "pixel (report: `errors.unshadowedPixels`, the error without them "
                        "`errors.visibilityExceptUnshadowed`, mask `<technique>_unshadowed.png` in the gallery)")};
}

MapOptions readMapOptions(const TechniqueArgs& args) {
  MapOptions o;
  o.size = args.integer("map");
  o.biasConstant = args.number("bias");
  o.biasSlope = args.number("slope-bias");
  o.maxHalfAngle = args.number("max-angle");
  return o;
}

ParamSpec pcfParam() {
  return ParamSpec::choice("pcf", "5", {"1", "5", "9"},
                           "PCF taps per map: 1, 5 (centre + 4 neighbours, the VWSS paper's) or 9 (3x3)");
}

int readPcfTaps(const TechniqueArgs& args) { return std::stoi(args.text("pcf")); }

void setBiasUniforms(const gl::Program& p, const MapOptions& o) {
  p.set("biasConstant", float(o.biasConstant));  // < 0: per point (shadow_map_common.glsl depthBias)
  p.set("biasSlope", float(o.biasSlope));
}

void renderDepthView(const std::string& technique, LightPass& pass, const MapFrame& frame, const glm::vec3& eye,
                     const gl::Framebuffer& fbo, const gl::Program& program, bool semiOpaque) {
  fbo.bind();
  const float zero = 0.0f;  // reversed depth: infinitely far
  glClearNamedFramebufferfv(fbo.id(), GL_DEPTH, 0, &zero);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  program.use();
  setMapUniforms(program, frame);
  program.set("eye", eye);
  drawWithOccluderCheck(technique, "shadow map", pass.scene, frame, eye, fbo.width(), [&] {
    pass.gpu.drawTriangles(1, GpuScene::Occluders::Opaque, program);
    if (semiOpaque) pass.gpu.drawTriangles(1, GpuScene::Occluders::SemiOpaque, program);
  });
  glDisable(GL_DEPTH_TEST);
}

bool opaqueTriangleCoversAPixel(const Scene& scene, const MapFrame& frame, const glm::vec3& eye, float zNear, int size,
                                bool cullBack) {
  auto project = [&](const glm::vec3& p, glm::vec2& px) {  // shadow_map_common.glsl viewClip
    const glm::vec3 r = p - eye;
    const float w = glm::dot(r, frame.axis);
    if (!(w > zNear)) return false;
    const glm::vec2 ndc(glm::dot(r, frame.right) / (frame.tanHalf * w), glm::dot(r, frame.up) / (frame.tanHalf * w));
    if (!(std::abs(ndc.x) < 1.0f && std::abs(ndc.y) < 1.0f)) return false;
    px = (ndc * 0.5f + 0.5f) * float(size);
    return true;
  };
  for (auto& m : scene.meshes) {
    if (scene.materials[std::size_t(m.material)].opacity < 1.0f) continue;  // not drawn as Occluders::Opaque
    if (scene.alphaTested(m.material)) continue;                            // its texture may cut every fragment
    for (auto& t : m.mesh.triangles) {
      const glm::vec3 a = m.mesh.positions[t[0]], b = m.mesh.positions[t[1]], c = m.mesh.positions[t[2]];
      if (cullBack && glm::dot(glm::cross(b - a, c - a), eye - a) <= 0.0f) continue;
      glm::vec2 pa, pb, pc;
      if (!project(a, pa) || !project(b, pb) || !project(c, pc)) continue;
      const float area = 0.5f * std::abs((pb.x - pa.x) * (pc.y - pa.y) - (pc.x - pa.x) * (pb.y - pa.y));
      const float perimeter = glm::length(pb - pa) + glm::length(pc - pb) + glm::length(pa - pc);
      if (perimeter > 0.0f && 2.0f * area / perimeter >= 1.0f) return true;
    }
  }
  return false;
}

void drawWithOccluderCheck(const std::string& technique, const std::string& what, const Scene& scene,
                           const MapFrame& frame, const glm::vec3& eye, int size, const std::function<void()>& draw) {
  gl::Query anySample(GL_ANY_SAMPLES_PASSED);
  anySample.begin();
  draw();
  anySample.end();
  if (anySample.result() == 0 && opaqueTriangleCoversAPixel(scene, frame, eye, frame.zNear, size, false))
    throw Error(technique, fmt::format("the {} pass drew no fragment although occluder triangles cover its {}^2 view "
                                       "(the GL ran no fragment or lost them)",
                                       what, size));
}

float NearestOccluder::get(const Scene& scene, int lightIndex, const glm::vec3& centre, const MapFrame& f,
                           bool surfaces) {
  auto key = std::make_tuple(lightIndex, std::array<float, 3>{f.axis.x, f.axis.y, f.axis.z}, surfaces);
  auto it = cache_.find(key);
  if (it != cache_.end()) return it->second;
  float nearest = std::numeric_limits<float>::infinity();
  auto depth = [&](const glm::vec3& v) { return glm::dot(v - centre, f.axis) - f.sampleAxialMax; };
  for (auto& m : scene.meshes) {
    if (!surfaces) {
      for (auto& v : m.mesh.positions) {
        float d = depth(v);
        if (d > f.zNear) nearest = std::min(nearest, d);
      }
      continue;
    }
    for (auto& t : m.mesh.triangles) {
      const float a = depth(m.mesh.positions[t.x]), b = depth(m.mesh.positions[t.y]), c = depth(m.mesh.positions[t.z]);
      const float lo = std::min({a, b, c}), hi = std::max({a, b, c});
      if (hi <= f.zNear) continue;  // behind the samples' near plane
      nearest = std::min(nearest, lo > f.zNear ? lo : f.zNear);
    }
  }
  return cache_.emplace(key, std::isfinite(nearest) ? nearest : 1.0f).first->second;
}

namespace {

// The views' reach around the light centre c in the frame (axis, right, up): of the samples, or
// of the light's whole extent (a rect's corners; a disk's rim, its radius times the sine between
// a direction and the normal; a sphere's ball).
void setReach(MapFrame& f, const Light& light, const LightSampleSet& samples, MapReach reach) {
  f.sampleLateral = f.sampleAxialMin = f.sampleAxialMax = 0.0f;
  auto add = [&](const glm::vec3& r) {
    f.sampleLateral = std::max({f.sampleLateral, std::abs(glm::dot(r, f.right)), std::abs(glm::dot(r, f.up))});
    f.sampleAxialMin = std::min(f.sampleAxialMin, glm::dot(r, f.axis));
    f.sampleAxialMax = std::max(f.sampleAxialMax, glm::dot(r, f.axis));
  };
  if (reach == MapReach::Samples) {
    for (auto& s : samples.positions) add(s - light.position);
    return;
  }
  const glm::vec3 t = light.tangent, b = light.bitangent(), n = glm::normalize(light.normal);
  switch (light.shape) {
    case LightShape::Point:
      break;
    case LightShape::Rect:
      for (float u : {-0.5f, 0.5f})
        for (float v : {-0.5f, 0.5f}) add(u * light.size.x * t + v * light.size.y * b);
      break;
    case LightShape::Disk: {
      auto rim = [&](const glm::vec3& d) {
        return light.size.x * std::sqrt(std::max(0.0f, 1.0f - glm::dot(d, n) * glm::dot(d, n)));
      };
      f.sampleLateral = std::max(rim(f.right), rim(f.up));
      f.sampleAxialMax = rim(f.axis), f.sampleAxialMin = -f.sampleAxialMax;
      break;
    }
    case LightShape::Sphere:
      f.sampleLateral = f.sampleAxialMax = light.size.x, f.sampleAxialMin = -light.size.x;
      break;
  }
}

// The largest float epsilon (shared/numerics.h penumbraSurfaceEpsilon) of the points the views start from.
float viewEpsilon(const Light& light, const LightSampleSet& samples, MapReach reach) {
  const glm::vec3 c = light.position;
  float eps = shared::penumbraSurfaceEpsilon(c);
  if (reach == MapReach::Samples) {
    for (const glm::vec3& s : samples.positions) eps = std::max(eps, shared::penumbraSurfaceEpsilon(s));
    return eps;
  }
  // The corners of the light's bounding box (its radius along every axis bounds a disk and a ball).
  const float r = light.shape == LightShape::Rect ? 0.5f * glm::length(light.size)
                  : light.isArea()                ? light.size.x
                                                  : 0.0f;
  for (float x : {-r, r})
    for (float y : {-r, r})
      for (float z : {-r, r}) eps = std::max(eps, shared::penumbraSurfaceEpsilon(c + glm::vec3(x, y, z)));
  return eps;
}

// The layout of shadow_map_fit.comp's storage block.
struct FitResult {
  glm::dvec4 centroid;  // xyz: sum of the surface positions, w: their count
  std::uint32_t tanHalfBits, outside, pad[6];
};
static_assert(sizeof(FitResult) == 64, "shadow_map_fit.comp: rows[] start at 64 bytes");

}  // namespace

MapFrame FrameFit::compute(const GpuScene& gpu, const Light& light, const LightSampleSet& samples,
                           const MapOptions& options, MapReach reach) {
  MapFrame f;
  f.size = options.size;
  f.layers = samples.setCount * samples.count;
  const glm::vec3 c = light.position;
  // The maps' near plane: 16 float epsilons of the views' positions (shared/numerics.h
  // penumbraSurfaceEpsilon), the distance below which a depth from a sample is rounding, not
  // geometry; it used to be 1e-5 of the scene's radius, which clipped occluders near the light in
  // a large scene. Reversed depth near / d keeps its relative precision at any near.
  f.zNear = 16.0f * viewEpsilon(light, samples, reach);

  const int w = gpu.width(), h = gpu.height();
  const std::size_t rowsBytes = std::size_t(h) * sizeof(glm::dvec4);
  if (!program_) program_ = gl::Program({"shadow_map_fit.comp"});
  if (result_.size() != sizeof(FitResult) + rowsBytes) result_ = gl::Buffer(sizeof(FitResult) + rowsBytes, nullptr);
  if (mask_.width() != w || mask_.height() != h) mask_ = gl::Texture::make2D(GL_R32UI, w, h);
  gpu.position().bind(PENUMBRA_UNIT_GBUF_POSITION);
  result_.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_MAP_FIT);
  program_.use();
  program_.set("size", glm::ivec2(w, h));
  FitResult out{};

  glm::vec3 hint = light.tangent;
  if (light.shape == LightShape::Rect || light.shape == LightShape::Disk) {
    f.axis = glm::normalize(light.normal);
  } else {
    // Isotropic lights: towards the receivers' centroid (a row's sum a thread, then the rows').
    program_.set("pass", 0);
    dispatchThreads(std::size_t(h));
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    program_.set("pass", 1);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    result_.read(&out.centroid, sizeof(out.centroid));
    const double n = out.centroid.w;
    glm::vec3 towards = n > 0.0 ? glm::vec3(glm::dvec3(out.centroid) / n) - c : glm::vec3(0.0f);
    f.axis = glm::length(towards) > f.zNear ? glm::normalize(towards) : glm::vec3(0.0f, -1.0f, 0.0f);
    hint = std::abs(f.axis.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  }
  f.right = hint - f.axis * glm::dot(hint, f.axis);
  if (glm::length(f.right) < 1e-6f) f.right = std::abs(f.axis.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  f.right = glm::normalize(f.right - f.axis * glm::dot(f.right, f.axis));
  // right x up = -axis: the handedness of a GL camera (x right, y up, looking down -z), so a
  // counter-clockwise front face stays counter-clockwise in every map (vwss culls back faces).
  f.up = glm::cross(f.right, f.axis);
  setReach(f, light, samples, reach);

  // Every receiver inside every view's frustum: seen from the view nearest to it along the axis
  // and farthest sideways (a thread a pixel; the widest receiver and the pixels outside).
  const std::uint32_t zero[2] = {0, 0};
  result_.write(zero, sizeof(zero), offsetof(FitResult, tanHalfBits));
  mask_.bindImage(PENUMBRA_IMAGE_MAP_OUTSIDE, GL_WRITE_ONLY);
  program_.set("pass", 2);
  program_.set("lightCentre", c);
  setMapUniforms(program_, f);  // the frame's axes and near plane (its tangent is still to fit)
  program_.set("reachLateral", f.sampleLateral);
  program_.set("reachAxialMax", f.sampleAxialMax);
  program_.set("tanMax", std::tan(glm::radians(float(options.maxHalfAngle))));
  dispatchThreads(std::size_t(w) * std::size_t(h));
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
  result_.read(&out.tanHalfBits, 2 * sizeof(std::uint32_t), offsetof(FitResult, tanHalfBits));
  float tanHalf = 0.0f;
  std::memcpy(&tanHalf, &out.tanHalfBits, sizeof(tanHalf));
  f.outsidePixels = outside_ = out.outside;
  if (tanHalf <= 0.0f) tanHalf = 1.0f;
  // Two texels of margin: the PCF taps of a receiver on the border stay in the map.
  f.tanHalf = tanHalf * (1.0f + 4.0f / float(f.size));
  gl::Context::checkErrors("shadow-map frustum fit");
  return f;
}

std::vector<std::uint8_t> FrameFit::outsideMask() const {
  if (outside_ == 0) return {};
  const std::vector<std::uint32_t> mask = mask_.readUint();
  return std::vector<std::uint8_t>(mask.begin(), mask.end());
}

void setMapUniforms(const gl::Program& p, const MapFrame& f) {
  p.set("mapAxis", f.axis);
  p.set("mapRight", f.right);
  p.set("mapUp", f.up);
  p.set("mapTanHalf", f.tanHalf);
  p.set("mapNear", f.zNear);
  p.set("mapSize", f.size);
}

std::size_t semiOpaqueTriangles(const Scene& scene) {
  std::size_t n = 0;
  for (auto& m : scene.meshes) {
    float opacity = scene.materials[std::size_t(m.material)].opacity;
    if (opacity > 0.0f && opacity < 1.0f) n += m.mesh.triangles.size();
  }
  return n;
}

// ---- MultiViewTechnique ----------------------------------------------------------------------

void MultiViewTechnique::prepare(const Scene& scene, GpuScene&) {
  semiOpaque_ = semiOpaqueTriangles(scene);
  maps_ = gl::Texture();
  semiCount_ = gl::Texture();
  semiLayers_ = gl::Texture();
  semiSlots_ = 0;
}

void MultiViewTechnique::renderSemiOpaque(LightPass& pass, const MapFrame& frame) {
  const gl::Program& semiProgram =
      programs_.get({"mvr_depth.vert", "mvr_depth.geom", "shadow_map_transmittance.frag"}, {"LAYERED"});
  if (!semiStatus_) {
    semiStatus_ = gl::Texture::make2D(GL_R32UI, 1, 1);
    semiFbo_ = gl::Framebuffer();
  }
  semiReruns_ = 0;
  for (;;) {
    const int slots = std::max(semiSlots_, 1);
    if (semiCount_.width() != frame.size || semiCount_.layers() != frame.layers ||
        semiLayers_.layers() != frame.layers * slots) {
      GLint maxLayers = 0;
      glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
      double bytes = 4.0 * double(frame.size) * frame.size * frame.layers * (slots + 1);
      if (frame.layers * slots > maxLayers || bytes > 4.0 * 1024 * 1024 * 1024)
        throw Error(name_,
                    fmt::format("{} semi-opaque surfaces on one map texel need {} layers ({:.0f} MiB) for {} maps of "
                                "{}^2: beyond this GL's {} layers or 4 GiB (use a smaller map)",
                                slots, frame.layers * slots, bytes / 1048576.0, frame.layers, frame.size, maxLayers));
      semiCount_ = gl::Texture::make2DArray(GL_R32UI, frame.size, frame.size, frame.layers);
      semiLayers_ = gl::Texture();
      semiLayers_ = gl::Texture::make2DArray(GL_R32UI, frame.size, frame.size, frame.layers * slots);
      semiFbo_ = gl::Framebuffer::empty(frame.size, frame.size, frame.layers);
    }
    semiCount_.clear(glm::vec4(0.0f));
    semiStatus_.clear(glm::vec4(0.0f));
    semiStatus_.bindImage(PENUMBRA_IMAGE_SEMI_STATUS, GL_READ_WRITE);
    semiCount_.bindImage(PENUMBRA_IMAGE_SEMI_COUNT, GL_READ_WRITE);
    semiLayers_.bindImage(PENUMBRA_IMAGE_SEMI_LAYERS, GL_WRITE_ONLY);
    semiFbo_.bind();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    semiProgram.use();
    setMapUniforms(semiProgram, frame);
    semiProgram.set("semiSlots", slots);
    pass.gpu.drawTriangles(frame.layers, GpuScene::Occluders::SemiOpaque, semiProgram);
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    const std::uint32_t most = semiStatus_.readUint().front();
    if (int(most) <= slots) {
      semiSlots_ = std::max(slots, int(most));
      return;
    }
    semiSlots_ = int(most);
    ++semiReruns_;
  }
}

const gl::Texture& MultiViewTechnique::ensureMaps(GLenum format, const MapFrame& frame) {
  if (maps_.format() != format || maps_.width() != frame.size || maps_.layers() != frame.layers) {
    GLint maxLayers = 0, maxSize = 0;
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    if (frame.layers > maxLayers)
      throw Error(name_, fmt::format("{} depth maps (sets x samples) exceed the GL's {} array layers", frame.layers,
                                     maxLayers));
    if (frame.size > maxSize) throw Error(name_, fmt::format("map size {} exceeds the GL's {}", frame.size, maxSize));
    maps_ = gl::Texture();
    try {
      maps_ = gl::Texture::make2DArray(format, frame.size, frame.size, frame.layers);
    } catch (const Error&) {  // GL_OUT_OF_MEMORY (gl/objects.cpp): name the technique and the parameter
      throw Error(name_, fmt::format("out of GPU memory for {} depth maps of {}^2 ({:.0f} MiB): use a smaller map",
                                     frame.layers, frame.size,
                                     4.0 * frame.size * double(frame.size) * frame.layers / 1048576.0));
    }
  }
  maps_.clear(glm::vec4(0.0f));
  return maps_;
}

const gl::Program& MultiViewTechnique::resolveProgram(bool perSample) {
  const bool semi = semiOpaque_ > 0;
  std::vector<std::string> defs = {"PCF_TAPS " + std::to_string(pcf_)};
  if (maps_.format() == GL_R32UI) defs.push_back("UINT_MAPS");
  if (perSample) defs.push_back("PER_SAMPLE_OUT");
  if (semi) defs.push_back("SEMI_OPAQUE");
  return programs_.get({"fullscreen.vert", "shadow_map_resolve.frag"}, defs);
}

void MultiViewTechnique::renderVisibility(LightPass& pass) {
  frame_ = pass.timer.time(
      name_ + " views", [&] { return fit_.compute(pass.gpu, pass.light, pass.samples, options_, MapReach::Samples); });
  renderMaps(pass, frame_);
  if (semiOpaque_) pass.timer.time(name_ + " semi-opaque maps", [&] { renderSemiOpaque(pass, frame_); });
  pass.timer.time(name_ + " lighting", [&] {
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    const gl::Program& prog = resolveProgram(pass.perSample != nullptr);
    setMapUniforms(prog, frame_);
    prog.set("eyePosition", pass.gpu.cameraPosition());
    setBiasUniforms(prog, options_);
    maps_.bind(PENUMBRA_UNIT_SHADOW_MAPS);
    if (semiOpaque_) {
      semiCount_.bind(PENUMBRA_UNIT_SEMI_COUNT);
      semiLayers_.bind(PENUMBRA_UNIT_SEMI_LAYERS);
      prog.set("semiSlots", semiSlots_);
    }
    if (pass.perSample) pass.perSample->bindImage(PENUMBRA_IMAGE_SAMPLE_VIS, GL_WRITE_ONLY);
    resolveVisibility(pass, prog);
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
  });
  gl::Context::checkErrors(name_.c_str());
}

std::vector<std::pair<std::string, double>> MultiViewTechnique::statistics() const {
  std::vector<std::pair<std::string, double>> s = {
      {"maps", frame_.layers},
      {"map size", frame_.size},
      {"pcf taps", pcf_},
      {"frustum half-angle deg", glm::degrees(std::atan(frame_.tanHalf))},
      {"pixels outside maps", double(frame_.outsidePixels)},
      {"map bytes", double(maps_.bytes())},
      {"semi-opaque triangles", double(semiOpaque_)},
      {"semi-opaque map bytes", double(semiCount_.bytes() + semiLayers_.bytes())},
      {"semi-opaque entries per texel", double(semiSlots_)},
      {"semi-opaque reruns", double(semiReruns_)},
  };
  addStatistics(s);
  return s;
}

void dispatchThreads(std::size_t threads) {
  const std::size_t groups =
      std::max<std::size_t>((threads + PENUMBRA_MAP_LOCAL_SIZE - 1) / PENUMBRA_MAP_LOCAL_SIZE, 1);
  const GLuint gx = GLuint(std::min<std::size_t>(groups, 65535)), gy = GLuint((groups + gx - 1) / gx);
  glDispatchCompute(gx, gy, 1);
}

int splatMaps(const gl::Program& program, const gl::Texture& maps, std::size_t threads, int layers,
              const SplatOptions& options) {
  if (threads == 0 || layers == 0) return 0;
  maps.bindImage(PENUMBRA_IMAGE_SHADOW_MAPS, GL_READ_WRITE);
  program.use();
  const int per = options.mapsPerThread <= 0 ? layers : std::min(options.mapsPerThread, layers);
  int dispatches = 0;
  for (int first = 0; first < layers; first += per) {
    program.set("firstLayer", first);
    program.set("layerCount", std::min(per, layers - first));
    dispatchThreads(threads);
    ++dispatches;
  }
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  return dispatches;
}

}  // namespace penumbra::shadow_map
