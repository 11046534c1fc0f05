#include "techniques/pcss/pcss.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "gl/context.h"
#include "pipeline/renderer.h"
#include "sampling/shared.hpp"
#include "techniques/shadow_map/maps.h"

namespace penumbra {
namespace {

// Half the side of the square of the light's area (rect, disk) or of the disc a sphere shows:
// the light "size" of the parallel-planes estimate.
float lightHalfSize(const Light& light) {
  switch (light.shape) {
    case LightShape::Rect:
    case LightShape::Disk: return 0.5f * std::sqrt(light.area());
    case LightShape::Sphere: return 0.5f * std::sqrt(float(M_PI)) * light.size.x;
    default: return 0.0f;
  }
}

const char* modeName(PcssMode m) {
  switch (m) {
    case PcssMode::PenumbraMask: return "penumbra mask";
    case PcssMode::MinFilter: return "min filter";
    case PcssMode::Fixed: return "fixed kernel";
    default: return "regular";
  }
}

// A single-channel float target and its framebuffer.
struct Target {
  gl::Texture texture;
  gl::Framebuffer fbo;
  void ensure(GLenum format, int w, int h) {
    if (texture.width() == w && texture.height() == h && texture.format() == format) return;
    fbo = gl::Framebuffer();
    texture = gl::Texture::make2D(format, w, h);
    fbo = gl::Framebuffer({&texture}, nullptr);
  }
};

class PercentageCloserSoftShadows final : public Technique {
 public:
  PercentageCloserSoftShadows(const shadow_map::MapOptions& m, const PcssOptions& o) : map_(m), o_(o) {}

  void prepare(const Scene& scene, GpuScene&) override {
    semiOpaque_ = shadow_map::semiOpaqueTriangles(scene);
    nearest_ = {};
  }

  void renderVisibility(LightPass& pass) override {
    frame_ = pass.timer.time("pcss views", [&] {
      return shadow_map::computeMapFrame(pass.scene, pass.light, pass.samples, pass.cpuGBuffer(), map_);
    });
    searchNear_ = nearest_.get(pass.scene, pass.lightIndex, pass.light.position, frame_);
    halfSize_ = lightHalfSize(pass.light);
    if (!vao_) {
      vao_ = gl::VertexArray::create();
      raw_ = gl::Sampler::make(false, 0.0f);
      compare_ = gl::Sampler::make(true, 0.0f, GL_GEQUAL);  // lit where the receiver is nearer or level
    }
    pass.timer.time("pcss shadow map", [&] {
      if (depth_.width() != frame_.size) {
        depthFbo_ = gl::Framebuffer();
        depth_ = gl::Texture::make2D(GL_DEPTH_COMPONENT32F, frame_.size, frame_.size);
        depthFbo_ = gl::Framebuffer(std::vector<gl::Framebuffer::Attachment>{}, &depth_);
      }
      shadow_map::renderDepthView(pass, frame_, pass.light.position, depthFbo_,
                                  program("depth", {"mvr_depth.vert", "depth_only.frag"}, {"CENTRAL"}), true);
    });
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    bindMap(pass);
    const int w = pass.gpu.width(), h = pass.gpu.height();
    const gl::Texture* aux = nullptr;
    if (o_.mode == PcssMode::MinFilter) {
      pass.timer.time("pcss min filter", [&] {
        // The window: the blocker search's reach at the farthest receivers, in texels.
        minRadius_ = o_.minRadius > 0 ? o_.minRadius
                                      : std::clamp(int(std::ceil(halfSize_ / (2.0f * searchNear_ * frame_.tanHalf) * float(frame_.size))), 1, 32);
        minA_.ensure(GL_R32F, frame_.size, frame_.size);
        minB_.ensure(GL_R32F, frame_.size, frame_.size);
        const gl::Program& mx = program("max", {"fullscreen.vert", "pcss_filter.frag"}, {"MAX_FILTER"});
        mx.set("radius", minRadius_);
        gl::Sampler::unbind(PENUMBRA_UNIT_PCSS_SOURCE);
        filter(mx, depth_, minA_, {1, 0});
        filter(mx, minA_.texture, minB_, {0, 1});
        if (o_.blur) blur(minB_, minA_);
      });
      aux = &minB_.texture;
    }
    if (o_.mode == PcssMode::PenumbraMask) {
      pass.timer.time("pcss penumbra mask", [&] {
        const int mw = (w + 1) / 2, mh = (h + 1) / 2;
        maskA_.ensure(GL_R32F, mw, mh);
        maskB_.ensure(GL_R32F, mw, mh);
        std::vector<std::string> defs;
        if (o_.noBlockerOne) defs.push_back("NO_BLOCKER_ONE");
        const gl::Program& pm = program(o_.noBlockerOne ? "mask1" : "mask", {"fullscreen.vert", "pcss_penumbra.frag"}, defs);
        setUniforms(pm, pass, o_.kernelScale);
        maskA_.fbo.bind();
        pass.gpu.bindGBuffer();
        bindMap(pass);
        pm.use();
        vao_.bind();
        glDrawArrays(GL_TRIANGLES, 0, 3);
        if (o_.blur) blur(maskA_, maskB_);
      });
      aux = &maskA_.texture;
    }

    pass.timer.time("pcss shadow mask", [&] {
      std::vector<std::string> defs;
      if (o_.mode == PcssMode::PenumbraMask) defs.push_back("PENUMBRA_MASK");
      if (o_.mode == PcssMode::MinFilter) defs.push_back("MIN_FILTER");
      if (o_.mode == PcssMode::Fixed) defs.push_back("FIXED");
      if (o_.checkerboard) defs.push_back("CHECKERBOARD");
      std::string key = "resolve";
      for (auto& d : defs) key += " " + d;
      const gl::Program& prog = program(key, {"fullscreen.vert", "pcss_resolve.frag"}, defs);
      setUniforms(prog, pass, 1.0);
      prog.set("screenSize", glm::vec2(float(w), float(h)));
      if (aux) {
        aux->bind(PENUMBRA_UNIT_PCSS_AUX);
        glTextureParameteri(aux->id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(aux->id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      }
      bindMap(pass);
      if (o_.checkerboard) {
        checker_.ensure(GL_RGBA32F, (w + 1) / 2, h);
        checker_.fbo.bind();
        pass.gpu.bindGBuffer();
        prog.use();
        setLightUniforms(prog, pass.light, pass.samples);
        vao_.bind();
        glDrawArrays(GL_TRIANGLES, 0, 3);
      } else {
        resolveVisibility(pass, prog);
      }
    });
    if (o_.checkerboard) {
      pass.timer.time("pcss checkerboard upsample", [&] {
        const gl::Program& up = program("checker", {"fullscreen.vert", "pcss_checker.frag"}, {});
        up.set("eyePosition", pass.gpu.cameraPosition());
        checker_.texture.bind(PENUMBRA_UNIT_PCSS_SOURCE);
        gl::Framebuffer fbo({&pass.visibility}, nullptr);
        fbo.bind();
        pass.gpu.bindGBuffer();
        up.use();
        vao_.bind();
        glDrawArrays(GL_TRIANGLES, 0, 3);
      });
    }
    gl::Sampler::unbind(PENUMBRA_UNIT_PCSS_DEPTH);
    gl::Sampler::unbind(PENUMBRA_UNIT_PCSS_COMPARE);
    gl::Context::checkErrors("pcss");
  }

  std::size_t memoryBytes() const override {
    return depth_.bytes() + minA_.texture.bytes() + minB_.texture.bytes() + maskA_.texture.bytes() +
           maskB_.texture.bytes() + checker_.texture.bytes();
  }

  std::vector<std::pair<std::string, double>> statistics() const override {
    return {{"map size", frame_.size},
            {"mode", double(int(o_.mode))},
            {"checkerboard", o_.checkerboard ? 1.0 : 0.0},
            {"blocker samples", o_.blockerSamples},
            {"pcf samples", o_.pcfSamples},
            {"kernel scale", o_.kernelScale},
            {"min filter radius", double(minRadius_)},
            {"frustum half-angle deg", glm::degrees(std::atan(frame_.tanHalf))},
            {"pixels outside maps", double(frame_.outsidePixels)},
            {"search near", searchNear_},
            {"light half size", halfSize_},
            {"map bytes", double(depth_.bytes())},
            {"semi-opaque triangles as opaque", double(semiOpaque_)}};
  }

 private:
  const gl::Program& program(const std::string& key, const std::vector<std::string>& files,
                             const std::vector<std::string>& defs) {
    auto it = programs_.find(key);
    if (it == programs_.end()) it = programs_.emplace(key, gl::Program(files, defs)).first;
    return it->second;
  }
  void bindMap(const LightPass&) const {
    depth_.bind(PENUMBRA_UNIT_PCSS_DEPTH);
    depth_.bind(PENUMBRA_UNIT_PCSS_COMPARE);
    raw_.bind(PENUMBRA_UNIT_PCSS_DEPTH);
    compare_.bind(PENUMBRA_UNIT_PCSS_COMPARE);
  }
  void setUniforms(const gl::Program& p, const LightPass& pass, double kernelScale) const {
    shadow_map::setMapUniforms(p, frame_);
    shadow_map::setBiasUniforms(p, map_, pass.scene);
    setLightUniforms(p, pass.light, pass.samples);
    p.set("eyePosition", pass.gpu.cameraPosition());
    p.set("surfaceOffset", pass.scene.surfaceOffset());
    p.set("lightHalfSize", halfSize_);
    p.set("searchNear", searchNear_);
    p.set("blockerSamples", o_.blockerSamples);
    p.set("pcfSamples", o_.pcfSamples);
    p.set("kernelScale", float(kernelScale));
  }
  // One separable pass of pcss_filter.frag from `source` into `target`.
  void filter(const gl::Program& p, const gl::Texture& source, Target& target, glm::ivec2 direction) {
    source.bind(PENUMBRA_UNIT_PCSS_SOURCE);
    p.use();
    p.set("direction", direction);
    target.fbo.bind();
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  // Sterna's 7x7 Gaussian (sigma 3) of `a`, back into `a` through `tmp`.
  void blur(Target& a, Target& tmp) {
    const gl::Program& g = program("gauss", {"fullscreen.vert", "pcss_filter.frag"}, {"GAUSSIAN"});
    filter(g, a.texture, tmp, {1, 0});
    filter(g, tmp.texture, a, {0, 1});
  }

  shadow_map::MapOptions map_;
  PcssOptions o_;
  shadow_map::MapFrame frame_;
  shadow_map::NearestOccluder nearest_;
  gl::Texture depth_;
  gl::Framebuffer depthFbo_;
  Target minA_, minB_, maskA_, maskB_, checker_;
  std::map<std::string, gl::Program> programs_;
  gl::Sampler raw_, compare_;
  gl::VertexArray vao_;
  std::size_t semiOpaque_ = 0;
  float searchNear_ = 0.0f, halfSize_ = 0.0f;
  int minRadius_ = 0;
};

}  // namespace

PcssOptions pcssPreset(PcssMode mode, bool ultra, bool checkerboard) {
  PcssOptions o;
  o.mode = mode;
  o.checkerboard = checkerboard;
  if (ultra) o.blockerSamples = 64, o.pcfSamples = 96;
  if (mode == PcssMode::PenumbraMask) o.kernelScale = 1.4;
  return o;
}

std::unique_ptr<Technique> makePercentageCloserSoftShadows(const TechniqueParams& params, PcssOptions o) {
  o.blockerSamples = params.getInt("blocker-samples", o.blockerSamples, 1, 256);
  o.pcfSamples = params.getInt("pcf-samples", o.pcfSamples, 1, 256);
  o.checkerboard = params.getBool("checkerboard", o.checkerboard);
  o.kernelScale = params.getDouble("kernel-scale", o.kernelScale, 0.25, 4.0);
  o.noBlockerOne = params.getBool("no-blocker-one", o.noBlockerOne);
  o.blur = params.getBool("blur", o.blur);
  o.minRadius = params.getInt("min-radius", o.minRadius, 0, 64);
  return std::make_unique<PercentageCloserSoftShadows>(shadow_map::readMapOptions(params), o);
}

}  // namespace penumbra
