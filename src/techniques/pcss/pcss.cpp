#include "techniques/pcss/pcss.h"

#include <algorithm>
#include <cmath>

#include "pipeline/renderer.h"
#include "shared/shared.h"  // NOLINT: shared with GLSL
#include "techniques/common/shadow_map/single_view.h"
#include "techniques/common/shadow_map/shaders/single_view_bindings.h"  // NOLINT: shared with GLSL

namespace penumbra {
namespace {

// A single-channel (or RGBA) float target and its framebuffer.
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

class PercentageCloserSoftShadows final : public shadow_map::SingleViewTechnique {
 public:
  PercentageCloserSoftShadows(const shadow_map::SingleViewOptions& m, const PcssOptions& o)
      : SingleViewTechnique("pcss", m), o_(o) {}

 protected:
  void renderShadow(LightPass& pass) override {
    const int w = pass.gpu.width(), h = pass.gpu.height();
    const gl::Texture* aux = nullptr;
    if (o_.mode == PcssMode::MinFilter) {
      pass.timer.time("pcss min filter", [&] {
        // The window: the blocker search's reach at the farthest receivers, in texels.
        const auto& f = frame();
        minRadius_ =
            o_.minRadius > 0
                ? o_.minRadius
                : std::clamp(int(std::ceil(lightHalfSize() / (2.0f * searchNear() * f.tanHalf) * float(f.size))), 1,
                             32);
        minA_.ensure(GL_R32F, f.size, f.size);
        minB_.ensure(GL_R32F, f.size, f.size);
        const gl::Program& mx = program({"fullscreen.vert", "pcss_filter.frag"}, {"MAX_FILTER"});
        mx.set("radius", minRadius_);
        gl::Sampler::unbind(PENUMBRA_UNIT_PCSS_SOURCE);
        filter(mx, depth(), minA_, {1, 0});
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
        const gl::Program& pm = program({"fullscreen.vert", "pcss_penumbra.frag"}, defs);
        setUniforms(pm, pass, o_.blockerSamples, o_.pcfSamples, o_.kernelScale);
        pass.gpu.bindGBuffer();
        bindMap();
        drawFullscreen(maskA_.fbo, pm);
        if (o_.blur) blur(maskA_, maskB_);
      });
      aux = &maskA_.texture;
    }

    pass.timer.time("pcss shadow mask", [&] {
      std::vector<std::string> defs;
      if (o_.mode == PcssMode::PenumbraMask) defs.push_back("PENUMBRA_MASK");
      if (o_.mode == PcssMode::MinFilter) defs.push_back("MIN_FILTER");
      if (o_.mode == PcssMode::Fixed) defs.push_back("FIXED");
      if (o_.mode == PcssMode::Dense) defs.push_back("DENSE");
      if (o_.checkerboard) defs.push_back("CHECKERBOARD");
      const gl::Program& prog = program({"fullscreen.vert", "pcss_resolve.frag"}, defs);
      setUniforms(prog, pass, o_.blockerSamples, o_.pcfSamples, 1.0);
      prog.set("screenSize", glm::vec2(float(w), float(h)));
      if (aux) {
        aux->bind(PENUMBRA_UNIT_PCSS_AUX);
        glTextureParameteri(aux->id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(aux->id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      }
      bindMap();
      if (o_.checkerboard) {
        checker_.ensure(GL_RGBA32F, (w + 1) / 2, h);
        pass.gpu.bindGBuffer();
        drawFullscreen(checker_.fbo, prog);
      } else {
        resolveVisibility(pass, prog);
      }
    });
    if (o_.checkerboard) {
      pass.timer.time("pcss checkerboard upsample", [&] {
        const gl::Program& up = program({"fullscreen.vert", "pcss_checker.frag"}, {});
        up.set("eyePosition", pass.gpu.cameraPosition());
        checker_.texture.bind(PENUMBRA_UNIT_PCSS_SOURCE);
        gl::Framebuffer fbo({&pass.visibility}, nullptr);
        pass.gpu.bindGBuffer();
        drawFullscreen(fbo, up);
      });
    }
  }

  std::size_t extraBytes() const override {
    return minA_.texture.bytes() + minB_.texture.bytes() + maskA_.texture.bytes() + maskB_.texture.bytes() +
           checker_.texture.bytes();
  }

  void addStatistics(std::vector<std::pair<std::string, double>>& out) const override {
    out.emplace_back("mode", double(int(o_.mode)));
    out.emplace_back("checkerboard", o_.checkerboard ? 1.0 : 0.0);
    out.emplace_back("blocker samples", o_.blockerSamples);
    out.emplace_back("pcf samples", o_.pcfSamples);
    out.emplace_back("kernel scale", o_.kernelScale);
    out.emplace_back("min filter radius", double(minRadius_));
  }

 private:
  // One separable pass of pcss_filter.frag from `source` into `target`.
  void filter(const gl::Program& p, const gl::Texture& source, Target& target, glm::ivec2 direction) {
    source.bind(PENUMBRA_UNIT_PCSS_SOURCE);
    p.set("direction", direction);
    drawFullscreen(target.fbo, p);
  }
  // Sterna's 7x7 Gaussian (sigma 3) of `a`, back into `a` through `tmp`.
  void blur(Target& a, Target& tmp) {
    const gl::Program& g = program({"fullscreen.vert", "pcss_filter.frag"}, {"GAUSSIAN"});
    filter(g, a.texture, tmp, {1, 0});
    filter(g, tmp.texture, a, {0, 1});
  }

  PcssOptions o_;
  Target minA_, minB_, maskA_, maskB_, checker_;
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

std::vector<ParamSpec> pcssParams(const PcssOptions& o) {
  std::vector<ParamSpec> p = shadow_map::singleViewParams(o.contact);
  p.push_back(
      ParamSpec::integer("blocker-samples", o.blockerSamples, 1, 256, "Vogel-disk samples of the blocker search"));
  p.push_back(ParamSpec::integer("pcf-samples", o.pcfSamples, 1, 256, "Vogel-disk samples of the PCF"));
  p.push_back(
      ParamSpec::boolean("checkerboard", o.checkerboard, "compute half the pixels, upsample the rest (Sterna 3)"));
  if (o.mode == PcssMode::PenumbraMask) {
    p.push_back(ParamSpec::number("kernel-scale", o.kernelScale, 0.25, 4.0,
                                  "blocker-search region scale of the mask (Sterna 2.2: 1.2-1.6)"));
    p.push_back(ParamSpec::boolean("no-blocker-one", o.noBlockerOne,
                                   "the mask holds the largest radius, not 0, where nothing blocks"));
  }
  if (o.mode == PcssMode::PenumbraMask || o.mode == PcssMode::MinFilter)
    p.push_back(ParamSpec::boolean("blur", o.blur, "the 7x7 Gaussian (sigma 3) of the mask / min map"));
  if (o.mode == PcssMode::MinFilter)
    p.push_back(ParamSpec::integer("min-radius", o.minRadius, 0, 64,
                                   "min-filter window half-size in texels; 0: the blocker search's reach, 1..32")
                    .shown("from the light"));
  return p;
}

std::unique_ptr<Technique> makePercentageCloserSoftShadows(const TechniqueArgs& args, PcssOptions o) {
  o.blockerSamples = args.integer("blocker-samples");
  o.pcfSamples = args.integer("pcf-samples");
  o.checkerboard = args.boolean("checkerboard");
  if (o.mode == PcssMode::PenumbraMask) {
    o.kernelScale = args.number("kernel-scale");
    o.noBlockerOne = args.boolean("no-blocker-one");
  }
  if (o.mode == PcssMode::PenumbraMask || o.mode == PcssMode::MinFilter) o.blur = args.boolean("blur");
  if (o.mode == PcssMode::MinFilter) o.minRadius = args.integer("min-radius");
  return std::make_unique<PercentageCloserSoftShadows>(shadow_map::readSingleView(args), o);
}

}  // namespace penumbra
