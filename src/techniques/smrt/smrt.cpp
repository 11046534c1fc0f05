#include "techniques/smrt/smrt.h"

#include "pipeline/renderer.h"
#include "techniques/common/shadow_map/single_view.h"

namespace penumbra {
namespace {

class ShadowMapRayTracing final : public shadow_map::SingleViewTechnique {
 public:
  ShadowMapRayTracing(const shadow_map::SingleViewOptions& m, const SmrtOptions& o)
      : SingleViewTechnique("smrt", m), o_(o) {}

 protected:
  void renderShadow(LightPass& pass) override {
    pass.timer.time("smrt trace", [&] {
      std::vector<std::string> defs;
      if (o_.extrapolate) defs.push_back("EXTRAPOLATE");
      const gl::Program& p = program({"fullscreen.vert", "smrt_resolve.frag"}, defs);
      setUniforms(p, pass, 0, 0, 1.0);
      p.set("rays", o_.rays);
      p.set("steps", o_.steps);
      p.set("spacing", float(o_.spacing));
      p.set("thickness", float(o_.thickness));
      p.set("slope", float(o_.slope));
      p.set("maxRayAngle", float(o_.maxRayAngle));
      p.set("jitter", o_.jitter ? 1 : 0);
      bindMap();
      resolveVisibility(pass, p);
    });
  }

  void addStatistics(std::vector<std::pair<std::string, double>>& out) const override {
    out.emplace_back("rays", o_.rays);
    out.emplace_back("steps per ray", o_.steps);
    out.emplace_back("step spacing", o_.spacing);
    out.emplace_back("extrapolate", o_.extrapolate ? 1.0 : 0.0);
    out.emplace_back("max ray angle", o_.maxRayAngle);
  }

 private:
  SmrtOptions o_;
};

}  // namespace

std::vector<ParamSpec> smrtParams(const SmrtOptions& o) {
  std::vector<ParamSpec> p = shadow_map::singleViewParams(o.contact);
  for (ParamSpec& s : p)
    if (s.key == "map") s = s.withDefault(o.mapSize);
  p.push_back(ParamSpec::integer("rays", o.rays, 1, 256,
                                 "rays a pixel, each to one of its light samples (all of them when rays >= samples)"));
  p.push_back(ParamSpec::integer("steps", o.steps, 1, 256, "map samples along each ray"));
  p.push_back(
      ParamSpec::number("spacing", o.spacing, 1.0, 8.0,
                        "step s of S at ((s + offset) / S)^spacing of the ray: 1 even, more near the receiver"));
  p.push_back(ParamSpec::boolean("extrapolate", o.extrapolate,
                                 "a ray that comes out from behind the map's layer nearer the light than the occluder "
                                 "it was behind (extrapolated with `slope`) hit it"));
  p.push_back(ParamSpec::number("slope", o.slope, 0.0, 1e3,
                                "extrapolation: the occluder's depth slope past where the ray left it, depth per "
                                "lateral world unit"));
  p.push_back(
      ParamSpec::number("thickness", o.thickness, 0.0, 1e3,
                        "a point behind the layer by less than this x the layer's depth is inside an occluder"));
  p.push_back(ParamSpec::number("max-ray-angle", o.maxRayAngle, 0.0, 3.2,
                                "radians a ray may span seen from the light centre, the rest unoccluded; 0: no limit"));
  p.push_back(
      ParamSpec::boolean("jitter", o.jitter, "per-pixel noise rotates the rays' samples and offsets their steps"));
  return p;
}

std::unique_ptr<Technique> makeShadowMapRayTracing(const TechniqueArgs& args, SmrtOptions o) {
  o.rays = args.integer("rays");
  o.steps = args.integer("steps");
  o.spacing = args.number("spacing");
  o.extrapolate = args.boolean("extrapolate");
  o.slope = args.number("slope");
  o.thickness = args.number("thickness");
  o.maxRayAngle = args.number("max-ray-angle");
  o.jitter = args.boolean("jitter");
  return std::make_unique<ShadowMapRayTracing>(shadow_map::readSingleView(args), o);
}

}  // namespace penumbra
