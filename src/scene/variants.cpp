#include "scene/variants.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace penumbra {
namespace {

// The variant's values by key, each checked; an unknown key or a pair without '=' fails.
struct Variant {
  double opacity = -1.0;  // < 0: as the scene has it
  int copies = 1;
  double spacing = 1.0;
};

Variant readVariant(const std::vector<std::string>& variant, const KeyPlace& place) {
  Variant v;
  for (const std::string& pair : variant) {
    const std::size_t eq = pair.find('=');
    if (eq == std::string::npos || eq == 0) place.fail("'" + abbreviate(pair) + "': expected key=value");
    const std::string key = pair.substr(0, eq);
    const KeyValue value = KeyValue::ofText(pair.substr(eq + 1));
    const KeyPlace at{place.where, place.at.empty() ? key : place.at + "." + key, place.code};
    if (key == "opacity")
      v.opacity = readNumber(value, at, 0.0, 1.0);
    else if (key == "copies")
      v.copies = readInteger(value, at, 1, 9);
    else if (key == "spacing") {
      v.spacing = readNumber(value, at, 0.0, 1e30);
      if (!(v.spacing > 0.0)) at.fail("must be greater than 0");
    } else
      at.fail("unknown scene variant key (known: " + joinKeys(sceneVariantKeys()) + ")");
  }
  return v;
}

}  // namespace

Scene withLightsScaled(Scene scene, double scale) {
  for (Light& l : scene.lights) l.size *= float(scale);
  return scene;
}

Scene withOccludersInstanced(const Scene& base, int copies, float spacing) {
  Scene s = base;
  static const glm::vec2 kCells[] = {{0, 0}, {1, 0}, {-1, 0}, {0, -1}, {1, -1}, {-1, -1}, {0, 1}, {1, 1}, {-1, 1}};
  for (int c = 1; c < copies && c < 9; ++c)
    for (std::size_t m = 1; m < base.meshes.size(); ++m) {
      SceneMesh copy = base.meshes[m];
      for (auto& p : copy.mesh.positions) p += glm::vec3(kCells[c].x * spacing, 0.0f, kCells[c].y * spacing);
      s.meshes.push_back(std::move(copy));
    }
  return s;
}

const std::vector<std::string>& sceneVariantKeys() {
  static const std::vector<std::string> keys = {"copies", "opacity", "spacing"};
  return keys;
}

void checkSceneVariant(const std::vector<std::string>& variant, const KeyPlace& place) { readVariant(variant, place); }

Scene applySceneVariant(Scene scene, const std::vector<std::string>& variant) {
  const Variant v = readVariant(variant, {"scene variant", "", ExitCode::Usage});
  if (v.opacity >= 0.0)
    for (Material& m : scene.materials) m.opacity = float(v.opacity);
  if (v.copies > 1) scene = withOccludersInstanced(scene, v.copies, float(v.spacing));
  return scene;
}

}  // namespace penumbra
