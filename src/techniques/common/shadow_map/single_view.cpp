#include "techniques/common/shadow_map/single_view.h"

#include <cmath>

#include "core/error.h"
#include "gl/context.h"
#include "pipeline/renderer.h"
#include "shared/shared.h"                                              // NOLINT: shared with GLSL
#include "techniques/common/shadow_map/shaders/single_view_bindings.h"  // NOLINT: shared with GLSL

namespace penumbra::shadow_map {

ParamSpec satBitsParam() {
  return ParamSpec::integer("sat-bits", 64, 32, 64, "precision of the summed-area table: 64 (doubles) or 32 (fp32)");
}

ParamSpec subKernelsParam(int fallback) {
  return ParamSpec::integer("sub-kernels", fallback, 1, 16,
                            "each kernel split into n x n sub-kernels with their own receiver depth");
}

int readSatBits(const TechniqueArgs& args) {
  const int bits = args.integer("sat-bits");
  if (bits != 32 && bits != 64)
    throw Error("param", "sat-bits: must be 32 or 64, got " + std::to_string(bits), ExitCode::Usage);
  return bits;
}

void SingleViewTechnique::prepare(const Scene& scene, GpuScene&) {
  semiOpaque_ = semiOpaqueTriangles(scene);
  nearest_ = {};
}

void SingleViewTechnique::renderVisibility(LightPass& pass) {
  frame_ = pass.timer.time(name_ + " views",
                           [&] { return fit_.compute(pass.gpu, pass.light, pass.samples, map_, MapReach::Light); });
  searchNear_ = nearest_.get(pass.scene, pass.lightIndex, pass.light.position, frame_);
  halfSize_ = pass.light.penumbraHalfSize();
  if (!vao_) {
    vao_ = gl::VertexArray::create();
    raw_ = gl::Sampler::make(false, 0.0f);
    compare_ = gl::Sampler::make(true, 0.0f, GL_GEQUAL);  // lit where the receiver is nearer or level
  }
  pass.timer.time(name_ + " shadow map", [&] {
    if (depth_.width() != frame_.size) {
      depthFbo_ = gl::Framebuffer();
      depth_ = gl::Texture::make2D(GL_DEPTH_COMPONENT32F, frame_.size, frame_.size);
      depthFbo_ = gl::Framebuffer(std::vector<gl::Framebuffer::Attachment>{}, &depth_);
    }
    renderDepthView(name_, pass, frame_, pass.light.position, depthFbo_,
                    program({"mvr_depth.vert", "depth_only.frag"}, {"CENTRAL"}), true);
  });
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  bindMap();
  renderShadow(pass);
  contact_.apply(pass, name_);
  gl::Sampler::unbind(PENUMBRA_UNIT_PCSS_DEPTH);
  gl::Sampler::unbind(PENUMBRA_UNIT_PCSS_COMPARE);
  gl::Context::checkErrors(name_.c_str());
}

SingleViewTechnique::DepthRange SingleViewTechnique::momentDepthRange(const LightPass& pass) {
  glm::vec3 lo, hi;
  pass.scene.bounds(lo, hi);
  float far = 0.0f;
  for (int c = 0; c < 8; ++c) {
    glm::vec3 corner((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
    far = std::max(far, glm::dot(corner - pass.light.position, frame_.axis));
  }
  // The nearest triangle point, not vertex: walls passing the light (a light inside a tube,
  // hard case 29) are nearer than any of their vertices, and clamped to a vertex's depth they
  // would occlude nothing.
  DepthRange r;
  r.min = std::min(nearestSurface(pass), far);
  r.max = std::max(far, r.min * 1.001f + 1e-6f);
  return r;
}

void SingleViewTechnique::buildMomentTable(gl::Buffer& sat, std::size_t bytesPerTexel,
                                           const std::vector<std::string>& defines, const DepthRange& range,
                                           const std::function<void(const gl::Program&)>& uniforms) {
  const std::size_t texels = std::size_t(frame_.size) * std::size_t(frame_.size);
  if (sat.size() != texels * bytesPerTexel) sat = gl::Buffer(texels * bytesPerTexel, nullptr);
  sat.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_VSSM_SAT);
  const gl::Program& p = program({"vssm_sat.comp"}, defines);
  p.set("satSize", frame_.size);
  p.set("mapNear", frame_.zNear);
  p.set("depthMin", range.min);
  p.set("depthMax", range.max);
  if (uniforms) uniforms(p);
  p.use();
  for (int pass = 0; pass < 3; ++pass) {
    p.set("pass", pass);
    dispatchThreads(pass == 0 ? texels : std::size_t(frame_.size));
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
}

void SingleViewTechnique::resolveMoments(LightPass& pass, const gl::Program& p, const gl::Buffer& sat,
                                         const DepthRange& range,
                                         const std::function<void(const gl::Program&)>& uniforms) {
  setUniforms(p, pass, 0, 0, 1.0);
  p.set("depthMin", range.min);
  p.set("depthMax", range.max);
  uniforms(p);
  sat.bindBase(GL_SHADER_STORAGE_BUFFER, PENUMBRA_SSBO_VSSM_SAT);
  bindMap();
  resolveVisibility(pass, p);
}

void SingleViewTechnique::momentStatistics(std::vector<std::pair<std::string, double>>& out, int satBits,
                                           const gl::Buffer& sat, const DepthRange& range) {
  out.emplace_back("sat bits", double(satBits));
  out.emplace_back("depth min", range.min);
  out.emplace_back("depth max", range.max);
  out.emplace_back("sat bytes", double(sat.size()));
}

void SingleViewTechnique::bindMap() const {
  depth_.bind(PENUMBRA_UNIT_PCSS_DEPTH);
  depth_.bind(PENUMBRA_UNIT_PCSS_COMPARE);
  raw_.bind(PENUMBRA_UNIT_PCSS_DEPTH);
  compare_.bind(PENUMBRA_UNIT_PCSS_COMPARE);
}

void SingleViewTechnique::setUniforms(const gl::Program& p, const LightPass& pass, int blockerSamples, int pcfSamples,
                                      double kernelScale) const {
  setMapUniforms(p, frame_);
  setBiasUniforms(p, map_);
  setLightUniforms(p, pass.light, pass.samples);
  p.set("eyePosition", pass.gpu.cameraPosition());
  p.set("lightHalfSize", halfSize_);
  p.set("searchNear", searchNear_);
  p.set("blockerSamples", blockerSamples);
  p.set("pcfSamples", pcfSamples);
  p.set("kernelScale", float(kernelScale));
}

const gl::Program& SingleViewTechnique::program(const std::vector<std::string>& files,
                                                const std::vector<std::string>& defines) {
  return programs_.get(files, defines);
}

void SingleViewTechnique::drawFullscreen(const gl::Framebuffer& fbo, const gl::Program& p) const {
  fbo.bind();
  p.use();
  vao_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

std::vector<std::pair<std::string, double>> SingleViewTechnique::statistics() const {
  std::vector<std::pair<std::string, double>> s = {{"map size", frame_.size},
                                                   {"frustum half-angle deg", glm::degrees(std::atan(frame_.tanHalf))},
                                                   {"pixels outside maps", double(frame_.outsidePixels)},
                                                   {"search near", searchNear_},
                                                   {"light half size", halfSize_},
                                                   {"map bytes", double(depth_.bytes())},
                                                   {"semi-opaque triangles as opaque", double(semiOpaque_)}};
  contact_.addStatistics(s);
  addStatistics(s);
  return s;
}

std::vector<ParamSpec> singleViewParams(const ContactOptions& contact) {
  std::vector<ParamSpec> p = mapParams();
  for (ParamSpec& c : contactParams(contact)) p.push_back(std::move(c));
  return p;
}

SingleViewOptions readSingleView(const TechniqueArgs& args) { return {readMapOptions(args), readContactOptions(args)}; }

}  // namespace penumbra::shadow_map
