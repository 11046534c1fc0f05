// The smrt folder's rows in the table of techniques (registry.h): smrt and its presets.
#include "techniques/registry.h"
#include "techniques/smrt/smrt.h"

namespace penumbra {

namespace {
TechniqueInfo smrtRow(std::string name, std::string description, SmrtOptions preset) {
  return presetRow(std::move(name), std::move(description), TechniqueFamily::SingleMap, smrtParams(preset), preset,
                   makeShadowMapRayTracing);
}
SmrtOptions unclamped() {
  SmrtOptions o;
  o.maxRayAngle = 0.0;
  return o;
}
SmrtOptions withContact() {
  SmrtOptions o;
  o.contact.enabled = true;
  return o;
}
SmrtOptions thicknessOnly() {
  SmrtOptions o = unclamped();
  o.extrapolate = false;
  o.thickness = 0.05;
  return o;
}
}  // namespace

std::vector<TechniqueInfo> smrtRows() {
  return {
      smrtRow("smrt",
              "shadow-map ray tracing as UE 5 ships it: 7 rays a pixel to its light samples, 8 steps each through one "
              "2048^2 map from the light centre, occluder extrapolation, rays clipped at 0.03 rad from the light",
              SmrtOptions{}),
      smrtRow("smrt-contact", "smrt (UE's defaults) with contact shadows multiplied in", withContact()),
      smrtRow("smrt-unclamped", "smrt with whole rays (no angle limit): every occluder between receiver and light",
              unclamped()),
      smrtRow("smrt-thickness",
              "smrt-unclamped without extrapolation: a step within 5% of the layer's depth behind it is a hit (the "
              "screen-space marcher's thickness rule)",
              thicknessOnly()),
  };
}

}  // namespace penumbra
