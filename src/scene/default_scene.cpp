// Scenes built in code: the default scene, the frame around a bare geometry file, and the
// procedural stained-glass texture. All are JSON documents so that --set overrides and the
// interpreter's validation apply to them exactly as to scene files.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/gtc/constants.hpp>

#include "scene/loaders.h"

namespace penumbra::detail {

namespace {

Json vec(glm::vec3 v) { return Json::array({v.x, v.y, v.z}); }

// Radiance that gives irradiance ~pi straight below a light of `area` at `distance`, so a
// white diffuse floor there shades to about its albedo.
float unitIrradianceRadiance(float distance, float area) { return glm::pi<float>() * distance * distance / area; }

std::uint32_t hash(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

float unitHash(std::uint32_t x) { return float(hash(x) & 0xffffffU) / float(0x1000000); }

}  // namespace

Image stainedGlassImage(int size) {
  // Voronoi panes around a jittered 4x4 grid of seeds: irregular like real leaded glass, and
  // deterministic (integer hash, no global RNG).
  constexpr int kGrid = 4;
  const glm::vec3 palette[] = {
      {1.00f, 0.06f, 0.04f}, {0.05f, 0.16f, 1.00f}, {1.00f, 0.72f, 0.05f}, {0.08f, 0.85f, 0.16f},
      {0.62f, 0.06f, 0.92f}, {0.05f, 0.80f, 0.92f}, {1.00f, 0.36f, 0.03f},
  };
  constexpr int kColors = int(sizeof(palette) / sizeof(palette[0]));
  std::vector<glm::vec2> seeds;
  std::vector<glm::vec3> colors;
  const float cell = float(size) / kGrid;
  for (int j = 0; j < kGrid; ++j) {
    for (int i = 0; i < kGrid; ++i) {
      const std::uint32_t id = std::uint32_t(j * kGrid + i);
      const glm::vec2 jitter(unitHash(2 * id + 1) * 0.7f + 0.15f, unitHash(2 * id + 2) * 0.7f + 0.15f);
      seeds.push_back((glm::vec2(i, j) + jitter) * cell);
      colors.push_back(palette[hash(id + 101) % kColors]);
    }
  }
  const glm::vec3 lead(0.015f);
  const float leadHalfWidth = std::max(0.6f, float(size) / 64.0f);  // ~1.2 px at 64^2
  Image img(size, size, 4, 1.0f);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const glm::vec2 p(float(x) + 0.5f, float(y) + 0.5f);
      float d1 = 1e30f, d2 = 1e30f;
      int nearest = 0;
      for (int k = 0; k < int(seeds.size()); ++k) {
        const float d = glm::length(p - seeds[std::size_t(k)]);
        if (d < d1) {
          d2 = d1;
          d1 = d;
          nearest = k;
        } else if (d < d2) {
          d2 = d;
        }
      }
      // (d2 - d1) / 2 is roughly the distance to the pane's border.
      const float border = std::min({p.x, p.y, float(size) - p.x, float(size) - p.y});
      const bool isLead = 0.5f * (d2 - d1) < leadHalfWidth || border < 2.0f * leadHalfWidth;
      // A gentle brightness ripple inside each pane, like uneven hand-made glass.
      const float ripple = 0.85f + 0.15f * std::cos(0.35f * (p.x + 1.7f * p.y) + float(nearest));
      const glm::vec3 c = isLead ? lead : colors[std::size_t(nearest)] * ripple;
      for (int ch = 0; ch < 3; ++ch) img.at(x, y, ch) = c[ch];
    }
  }
  return img;
}

Json framingCamera(glm::vec3 lo, glm::vec3 hi) {
  const glm::vec3 centre = 0.5f * (lo + hi);
  const float radius = std::max(0.5f * glm::length(hi - lo), 1e-3f);
  const float fov = 40.0f;
  const float distance = 1.05f * radius / std::sin(glm::radians(0.5f * fov));
  const glm::vec3 position = centre + glm::normalize(glm::vec3(0.0f, 0.45f, 1.0f)) * distance;
  return {{"position", vec(position)},
          {"target", vec(centre)},
          {"up", vec({0, 1, 0})},
          {"fov", fov},
          {"near", 0.01f * distance}};
}

Json bareGeometryDocument(const std::string& fileName, glm::vec3 lo, glm::vec3 hi) {
  const glm::vec3 centre = 0.5f * (lo + hi);
  const float radius = std::max(0.5f * glm::length(hi - lo), 1e-3f);
  // The floor sits a hair below the model so that faces resting on it are not coplanar.
  const float floorY = lo.y - 1e-3f * radius;
  const float lightY = hi.y + 2.0f * radius;
  const float lightSize = radius;
  Json doc;
  doc["description"] = "bare geometry file framed by penumbra: floor, camera, rect light";
  doc["camera"] = framingCamera(lo, hi);
  doc["materials"] = Json::array({{{"name", "floor"}, {"baseColor", vec(glm::vec3(0.75f))}}});
  doc["objects"] = Json::array({
      {{"name", "model"}, {"file", fileName}},
      {{"name", "floor"},
       {"shape", "plane"},
       {"size", 8.0f * radius},
       {"translate", vec({centre.x, floorY, centre.z})},
       {"material", "floor"}},
  });
  doc["lights"] = Json::array({{
      {"name", "key"},
      {"type", "rect"},
      {"position", vec({centre.x, lightY, centre.z})},
      {"normal", vec({0, -1, 0})},
      {"tangent", vec({1, 0, 0})},
      {"size", Json::array({lightSize, lightSize})},
      {"intensity", unitIrradianceRadiance(lightY - floorY, lightSize * lightSize)},
  }});
  return doc;
}

Json defaultSceneDocument() {
  // A stained-glass window overhead; occluders at several heights so that penumbra widths
  // range from nearly hard (the low step) to very soft (the floating plate near the light).
  const float lightY = 4.0f;
  const float lightSize = 2.4f;
  Json doc;
  doc["name"] = "default";
  doc["description"] = "built-in scene: stained-glass rect light over occluders of several heights";
  doc["resolution"] = Json::array({256, 256});
  doc["background"] = vec(glm::vec3(0.02f));
  doc["camera"] = {{"position", vec({0.0f, 3.6f, 7.0f})},
                   {"target", vec({0.0f, 0.7f, 0.0f})},
                   {"up", vec({0, 1, 0})},
                   {"fov", 45.0f},
                   {"near", 0.05f}};
  doc["materials"] = Json::array({
      {{"name", "floor"}, {"baseColor", vec(glm::vec3(0.8f))}},
      {{"name", "stone"}, {"baseColor", vec({0.72f, 0.64f, 0.55f})}},
      {{"name", "metal"}, {"baseColor", vec({0.55f, 0.58f, 0.62f})}},
  });
  doc["objects"] = Json::array({
      {{"name", "floor"}, {"shape", "plane"}, {"size", 14.0f}, {"material", "floor"}},
      {{"name", "tower"},
       {"shape", "box"},
       {"size", vec({0.5f, 2.4f, 0.5f})},
       {"translate", vec({-1.5f, 1.2f, -0.6f})},
       {"rotate", vec({0.0f, 25.0f, 0.0f})},
       {"material", "stone"}},
      {{"name", "post"},
       {"shape", "cylinder"},
       {"radius", 0.05f},
       {"height", 1.6f},
       {"segments", 16},
       {"translate", vec({1.3f, 0.8f, -0.2f})},
       {"material", "metal"}},
      {{"name", "ball"},
       {"shape", "sphere"},
       {"radius", 0.45f},
       {"translate", vec({1.3f, 2.05f, -0.2f})},
       {"material", "metal"}},
      {{"name", "plate"},
       {"shape", "box"},
       {"size", vec({1.1f, 0.04f, 0.7f})},
       {"translate", vec({0.0f, 1.3f, 1.2f})},
       {"rotate", vec({0.0f, -20.0f, 0.0f})},
       {"material", "stone"}},
      {{"name", "step"},
       {"shape", "box"},
       {"size", vec({1.2f, 0.3f, 0.8f})},
       {"translate", vec({-0.2f, 0.15f, -1.9f})},
       {"material", "stone"}},
  });
  // The texture averages about half its peak: twice the unit-irradiance radiance.
  doc["lights"] = Json::array({{
      {"name", "window"},
      {"type", "rect"},
      {"position", vec({0.0f, lightY, 0.0f})},
      {"normal", vec({0, -1, 0})},
      {"tangent", vec({1, 0, 0})},
      {"size", Json::array({lightSize, lightSize})},
      {"intensity", 2.0f * unitIrradianceRadiance(lightY, lightSize * lightSize)},
      {"texture", "procedural:stained-glass"},
  }});
  return doc;
}

}  // namespace penumbra::detail
