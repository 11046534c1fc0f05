// glTF 2.0 to penumbra meshes, materials and lights. gltf_validate.cpp has already checked the
// container, URIs and buffer/bufferView bounds; gltf_primitives.cpp converts the primitives;
// here the node graph is checked for cycles and shared children, and the hierarchy is flattened
// to the file's space (mirrored instances get reversed winding).
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <limits>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "core/error.h"
#include "core/memory.h"
#include "scene/gltf_compression.h"
#include "scene/gltf_loader.h"

namespace penumbra::detail {

namespace {

// ---------------------------------------------------------------------------------------------

void convertMaterials(Loader& L) {
  std::map<std::pair<int, bool>, int> textureOfImage;  // (image, sRGB) -> Scene::textures
  for (std::size_t i = 0; i < L.gltf.materials.size(); ++i) {
    const tinygltf::Material& g = L.gltf.materials[i];
    const std::string what = "material " + std::to_string(i);
    Material m;
    m.name = g.name.empty() ? L.file + "#" + what : g.name;
    const auto& factor = g.pbrMetallicRoughness.baseColorFactor;
    float alpha = 1.0f;
    if (factor.size() == 4) {
      m.baseColor = glm::vec3(float(factor[0]), float(factor[1]), float(factor[2]));
      alpha = float(factor[3]);
    }
    if (!std::isfinite(alpha) || !std::isfinite(m.baseColor.x + m.baseColor.y + m.baseColor.z)) {
      L.fail(what + ": baseColorFactor is not finite");
    }
    if (glm::any(glm::lessThan(m.baseColor, glm::vec3(0.0f))) ||
        glm::any(glm::greaterThan(m.baseColor, glm::vec3(1.0f))) || alpha < 0.0f || alpha > 1.0f)
      L.warn(what + ": baseColorFactor outside [0, 1], clamped");
    m.baseColor = glm::clamp(m.baseColor, 0.0f, 1.0f);
    alpha = std::clamp(alpha, 0.0f, 1.0f);
    // What the material holds that penumbra does not shade: said, not dropped silently.
    for (const auto& [name, ext] : g.extensions)
      if (name != "KHR_materials_emissive_strength")
        L.warn(what + ": extension " + name + " is not used" +
               (name == "KHR_materials_pbrSpecularGlossiness" ? " (shaded as metallic-roughness from its base factors)"
                                                              : ""));
    if (g.emissiveFactor.size() == 3 &&
        (g.emissiveFactor[0] != 0.0 || g.emissiveFactor[1] != 0.0 || g.emissiveFactor[2] != 0.0))
      L.warn(what + ": emissiveFactor is not used (surfaces do not emit; lights do)");
    m.alphaCutoff = float(g.alphaCutoff);
    if (g.alphaMode == "MASK") {
      m.alphaMode = AlphaMode::Mask;
      m.alphaFactor = alpha;
      m.opacity = alpha >= m.alphaCutoff ? 1.0f : 0.0f;
    } else if (g.alphaMode == "BLEND") {
      m.alphaMode = AlphaMode::Blend;
      m.opacity = alpha;
    } else if (!g.alphaMode.empty() && g.alphaMode != "OPAQUE") {
      L.warn(what + ": unknown alphaMode '" + g.alphaMode + "', treated as OPAQUE");
    }
    // A texture slot's image, decoded once per (image, colour space) and shared by materials.
    auto textureOf = [&](const tinygltf::TextureInfo& info, const char* slot, bool srgb) -> int {
      const int tex = info.index;
      if (tex < 0) return -1;
      if (std::size_t(tex) >= L.gltf.textures.size()) {
        L.fail(what + ": " + slot + " " + std::to_string(tex) + " does not exist");
      }
      if (info.texCoord != 0) {
        L.warn(what + ": " + slot + " uses TEXCOORD_" + std::to_string(info.texCoord) + "; only TEXCOORD_0 is loaded");
      }
      if (info.extensions.count("KHR_texture_transform")) L.warn(what + ": KHR_texture_transform ignored");
      const int image = L.gltf.textures[std::size_t(tex)].source;
      if (image < 0 || std::size_t(image) >= L.gltf.images.size()) {
        L.warn(what + ": texture " + std::to_string(tex) + " has no image; " + slot + " ignored");
        return -1;
      }
      const std::pair<int, bool> key{image, srgb};
      if (const auto it = textureOfImage.find(key); it != textureOfImage.end()) return it->second;
      const tinygltf::Image& img = L.gltf.images[std::size_t(image)];
      Texture t;
      t.source = L.path +
                 (img.uri.empty() || img.uri.rfind("data:", 0) == 0 ? "#image" + std::to_string(image) : "#" + img.uri);
      std::string why = "no data";
      const bool readable = !img.image.empty() && encodedImageSize(img.image, t.width, t.height, why);
      if (!readable || (L.options.decodeTextures && !decodeGltfImage(img.image, t.image, why, srgb))) {
        L.warn(what + ": image " + std::to_string(image) + ": " + why + "; " + slot + " ignored");
        return -1;
      }
      const int index = int(L.out.textures.size());
      textureOfImage[key] = index;
      L.out.textures.push_back(std::move(t));
      return index;
    };
    m.baseColorTexture = textureOf(g.pbrMetallicRoughness.baseColorTexture, "baseColorTexture", true);
    if (m.baseColorTexture >= 0 && m.alphaMode == AlphaMode::Blend) {
      std::ostringstream opacity;
      opacity << m.opacity;
      L.warn(what + ": alphaMode BLEND: texture alpha is not used for shadows (constant opacity " + opacity.str() +
             "; MASK is alpha-tested)");
    }
    // The specification's BRDF (Appendix B); factors default to 1 (tinygltf fills them in).
    m.brdf = BrdfModel::MetallicRoughness;
    const double metallic = g.pbrMetallicRoughness.metallicFactor, roughness = g.pbrMetallicRoughness.roughnessFactor;
    if (!std::isfinite(metallic) || !std::isfinite(roughness))
      L.fail(what + ": metallicFactor or roughnessFactor is not finite");
    m.metallic = std::clamp(float(metallic), 0.0f, 1.0f);
    m.roughness = std::clamp(float(roughness), 0.0f, 1.0f);
    // Linear data (the specification: "texture ... MUST be ... linear"): not sRGB-decoded.
    m.metallicRoughnessTexture =
        textureOf(g.pbrMetallicRoughness.metallicRoughnessTexture, "metallicRoughnessTexture", false);
    for (const auto& [slot, info] : {std::pair<const char*, int>{"normalTexture", g.normalTexture.index},
                                     {"occlusionTexture", g.occlusionTexture.index},
                                     {"emissiveTexture", g.emissiveTexture.index}})
      if (info >= 0) L.warn(what + ": " + slot + " is not used (penumbra shades with vertex normals, no emission)");
    L.out.materials.push_back(std::move(m));
  }
}

// ---------------------------------------------------------------------------------------------

glm::dmat4 localMatrix(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) return glm::make_mat4(n.matrix.data());
  glm::dmat4 m(1.0);
  if (n.translation.size() == 3) m = glm::translate(m, glm::make_vec3(n.translation.data()));
  if (n.rotation.size() == 4) {
    // glTF stores x, y, z, w; glm's quaternion constructor takes w first.
    glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
    const double len = glm::length(q);
    q = len > 0.0 ? q / len : glm::dquat(std::nan(""), 0, 0, 0);
    m = m * glm::mat4_cast(q);
  }
  if (n.scale.size() == 3) m = glm::scale(m, glm::make_vec3(n.scale.data()));
  return m;
}

// A usable world matrix: finite as the float matrix it is applied as (a double beyond float
// range would become Inf, and converting it is undefined behaviour), and not (nearly)
// collapsing space onto a plane. The determinant is compared with the product of the column
// lengths, so scale does not matter.
bool usable(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      if (!(std::abs(m[c][r]) <= double(std::numeric_limits<float>::max()))) return false;
    }
  }
  const glm::dmat3 l(m);
  const double volume = glm::length(l[0]) * glm::length(l[1]) * glm::length(l[2]);
  return std::abs(glm::determinant(l)) > 1e-12 * volume;
}

// Checks the node graph: children exist, each node has at most one parent, no cycles.
// Returns the parent of every node (-1 for roots).
std::vector<int> checkHierarchy(const Loader& L) {
  const std::size_t count = L.gltf.nodes.size();
  std::vector<int> parent(count, -1);
  for (std::size_t i = 0; i < count; ++i) {
    for (int c : L.gltf.nodes[i].children) {
      if (c < 0 || std::size_t(c) >= count) {
        L.fail("node " + std::to_string(i) + ": child " + std::to_string(c) + " does not exist");
      }
      if (std::size_t(c) == i) L.fail("node " + std::to_string(i) + " is its own child");
      if (parent[std::size_t(c)] >= 0) {
        L.fail("node " + std::to_string(c) + " has two parents (nodes " + std::to_string(parent[std::size_t(c)]) +
               " and " + std::to_string(i) + ")");
      }
      parent[std::size_t(c)] = int(i);
    }
  }
  // With one parent each, a cycle is a chain of parents that never reaches a root.
  std::vector<char> state(count, 0);  // 0 unseen, 1 on the current walk, 2 reaches a root
  for (std::size_t start = 0; start < count; ++start) {
    std::vector<std::size_t> walk;
    for (std::size_t n = start; state[n] != 2;) {
      if (state[n] == 1) L.fail("node hierarchy has a cycle through node " + std::to_string(n));
      state[n] = 1;
      walk.push_back(n);
      if (parent[n] < 0) break;
      n = std::size_t(parent[n]);
    }
    for (std::size_t w : walk) state[w] = 2;
  }
  return parent;
}

void addLight(Loader& L, Light light, const glm::dmat4& world, const std::string& what, const std::string& node) {
  Light placed = transformLight(light, glm::mat4(world));
  // A light definition used by several nodes: each placed light is named by its node too (names
  // must differ: they name a light's files and rows).
  const bool taken =
      std::any_of(L.out.lights.begin(), L.out.lights.end(), [&](const Light& l) { return l.name == what; });
  placed.name = taken ? what + "@" + node : what;
  L.out.lights.push_back(std::move(placed));
}

void nodeLights(Loader& L, std::size_t index, const glm::dmat4& world, const std::string& label) {
  const Json& node = L.json["nodes"][index];
  const auto ext = node.find("extensions");
  if (ext == node.end() || !ext->is_object()) return;
  auto lightIndex = [&](const char* name, const Json*& defs) -> int {
    const auto e = ext->find(name);
    if (e == ext->end()) return -1;
    const auto top = L.json.find("extensions");
    const Json* lights = nullptr;
    if (top != L.json.end() && top->contains(name) && (*top)[name].contains("lights")) {
      lights = &(*top)[name]["lights"];
    }
    if (!e->is_object() || !e->contains("light") || !(*e)["light"].is_number_unsigned() || !lights ||
        !lights->is_array() || (*e)["light"].get<std::size_t>() >= lights->size()) {
      L.fail(label + ": " + name + " light reference is invalid");
    }
    defs = lights;
    return (*e)["light"].get<int>();
  };
  // A colour that is not three numbers was read as white; a negative part is refused with the
  // light's other values (scene_json.cpp, for every light of the scene).
  auto color = [&](const Json& def) {
    glm::vec3 c(1.0f);
    if (!def.contains("color")) return c;
    const Json& v = def["color"];
    if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
      L.fail(label + ": a light's color must be 3 numbers, got " + shownJson(v));
    for (int k = 0; k < 3; ++k) c[k] = v[std::size_t(k)].get<float>();
    return c;
  };
  const Json* defs = nullptr;
  if (const int i = lightIndex("KHR_lights_punctual", defs); i >= 0) {
    const Json& def = (*defs)[std::size_t(i)];
    const std::string type = def.value("type", "");
    const std::string what = label + " KHR_lights_punctual " + std::to_string(i);
    if (type == "directional") {
      L.warn(what + ": directional lights are not supported; dropped");
    } else if (type == "point" || type == "spot") {
      if (type == "spot") L.warn(what + ": spot light treated as a point light");
      Light light;
      light.shape = LightShape::Point;
      light.position = glm::vec3(0.0f);
      light.color = color(def);
      light.intensity = def.value("intensity", 1.0f);
      if (def.contains("range")) L.warn(what + ": range is not used (the light's falloff is 1/r^2 everywhere)");
      addLight(L, light, world, def.value("name", what), label);
    } else {
      L.fail(what + ": unknown light type '" + type + "'");
    }
  }
  if (const int i = lightIndex("EXT_lights_area", defs); i >= 0) {
    const Json& def = (*defs)[std::size_t(i)];
    const std::string type = def.value("type", "");
    const std::string what = label + " EXT_lights_area " + std::to_string(i);
    // Following the draft as Babylon.js reads it: "size" is the height (rect, along local Y)
    // or the diameter (disk); rect width = size * rect.aspect. Emission along local -Z.
    const float size = def.value("size", 1.0f);
    float aspect = 1.0f;
    if (def.contains("rect") && def["rect"].is_object()) aspect = def["rect"].value("aspect", 1.0f);
    if (!(size > 0.0f) || !(aspect > 0.0f) || !std::isfinite(size * aspect)) {
      L.fail(what + ": size and rect.aspect must be positive");
    }
    Light light;
    light.position = glm::vec3(0.0f);
    light.normal = {0.0f, 0.0f, -1.0f};
    light.tangent = {1.0f, 0.0f, 0.0f};
    light.color = color(def);
    light.intensity = def.value("intensity", 1.0f);
    if (type == "rect") {
      light.shape = LightShape::Rect;
      light.size = {size * aspect, size};
    } else if (type == "disk") {
      light.shape = LightShape::Disk;
      light.size = glm::vec2(0.5f * size);
    } else {
      L.fail(what + ": unknown area light type '" + type + "'");
    }
    addLight(L, light, world, def.value("name", what), label);
  }
}

}  // namespace

// The default scene's root nodes (every parentless node when the file names no scene).
std::vector<int> sceneRoots(Loader& L, const std::vector<int>& parent) {
  const tinygltf::Model& gltf = L.gltf;
  std::vector<int> roots;
  if (gltf.defaultScene < 0 && gltf.scenes.empty()) {
    for (std::size_t n = 0; n < gltf.nodes.size(); ++n)
      if (parent[n] < 0) roots.push_back(int(n));
    return roots;
  }
  const int s = std::max(gltf.defaultScene, 0);
  if (std::size_t(s) >= gltf.scenes.size()) L.fail("scene " + std::to_string(s) + " does not exist");
  std::vector<bool> listed(gltf.nodes.size(), false);
  for (int n : gltf.scenes[std::size_t(s)].nodes) {
    if (n < 0 || std::size_t(n) >= gltf.nodes.size())
      L.fail("scene " + std::to_string(s) + ": node " + std::to_string(n) + " does not exist");
    if (parent[std::size_t(n)] >= 0)
      L.fail("scene " + std::to_string(s) + " lists node " + std::to_string(n) + ", which is a child of node " +
             std::to_string(parent[std::size_t(n)]));
    if (listed[std::size_t(n)]) L.fail("scene " + std::to_string(s) + " lists node " + std::to_string(n) + " twice");
    listed[std::size_t(n)] = true;
    roots.push_back(n);
  }
  return roots;
}

// Triangles a primitive declares (its index or vertex count), before anything is read; 0 for an
// accessor its bufferView cannot hold (converting it names that).
double declaredTriangles(const tinygltf::Model& gltf, const tinygltf::Primitive& p) {
  const auto position = p.attributes.find("POSITION");
  const int index = p.indices >= 0 ? p.indices : position != p.attributes.end() ? position->second : -1;
  if (index < 0 || std::size_t(index) >= gltf.accessors.size()) return 0.0;
  const tinygltf::Accessor& accessor = gltf.accessors[std::size_t(index)];
  const double count = double(accessor.count);
  // A Draco primitive's accessors have no bufferView: the counts they declare are what the stream
  // must decode to (decodeDraco checks).
  if (!hasDraco(p)) {
    if (accessor.bufferView < 0 || std::size_t(accessor.bufferView) >= gltf.bufferViews.size()) return 0.0;
    const double element = double(tinygltf::GetComponentSizeInBytes(std::uint32_t(accessor.componentType))) *
                           double(tinygltf::GetNumComponentsInType(std::uint32_t(accessor.type)));
    if (!(element > 0.0) || count * element > double(gltf.bufferViews[std::size_t(accessor.bufferView)].byteLength))
      return 0.0;
  }
  if (p.mode == TINYGLTF_MODE_TRIANGLES || p.mode < 0) return std::floor(count / 3.0);
  if (p.mode == TINYGLTF_MODE_TRIANGLE_STRIP || p.mode == TINYGLTF_MODE_TRIANGLE_FAN) return std::max(0.0, count - 2.0);
  return 0.0;
}

// What the file will take before a triangle is placed or a texel decoded: the triangles of every
// mesh instance the scene's nodes place (a 2 MB file can place one mesh on 20,000 nodes) and the
// texels of every image a material uses, from the images' headers. Refused with the estimate
// when it does not fit (core/memory.h).
void checkMemoryNeeds(Loader& L, const std::vector<int>& roots) {
  const tinygltf::Model& gltf = L.gltf;
  double triangles = 0.0;
  std::size_t instances = 0;
  std::vector<int> stack(roots.rbegin(), roots.rend());  // a tree: checkHierarchy refused cycles
  while (!stack.empty()) {
    const tinygltf::Node& node = gltf.nodes[std::size_t(stack.back())];
    stack.pop_back();
    stack.insert(stack.end(), node.children.begin(), node.children.end());
    if (node.mesh < 0 || std::size_t(node.mesh) >= gltf.meshes.size()) continue;
    ++instances;
    for (const tinygltf::Primitive& p : gltf.meshes[std::size_t(node.mesh)].primitives)
      triangles += declaredTriangles(gltf, p);
  }
  checkMemory(
      L.path,
      fmt::format("placing {:.0f} triangles ({} mesh instances on {} nodes)", triangles, instances, gltf.nodes.size()),
      triangles * kCleanBytesPerTriangle);
  if (!L.options.decodeTextures) return;
  std::vector<bool> used(gltf.images.size(), false);
  auto use = [&](int texture) {
    if (texture < 0 || std::size_t(texture) >= gltf.textures.size()) return;
    const int image = gltf.textures[std::size_t(texture)].source;
    if (image >= 0 && std::size_t(image) < used.size()) used[std::size_t(image)] = true;
  };
  for (const tinygltf::Material& m : gltf.materials) {
    use(m.pbrMetallicRoughness.baseColorTexture.index);
    use(m.pbrMetallicRoughness.metallicRoughnessTexture.index);
  }
  double bytes = 0.0, texels = 0.0;
  std::size_t images = 0;
  for (std::size_t i = 0; i < used.size(); ++i) {
    int w = 0, h = 0;
    std::string why;
    if (!used[i] || !encodedImageSize(gltf.images[i].image, w, h, why)) continue;  // warned when converted
    ++images;
    texels += double(w) * double(h);
    bytes += decodeBytes(w, h);
  }
  checkMemory(L.path, fmt::format("decoding its {} images ({:.0f} texels)", images, texels), bytes);
}

Model loadGltf(const std::string& path, const LoadOptions& options) {
  Model out;
  tinygltf::Model gltf;
  Json json;
  parseGltfSandboxed(path, gltf, json, out.warnings);
  Loader L{path, std::filesystem::path(path).filename().string(), gltf, json, out, options};
  try {
    L.quantized = std::find(gltf.extensionsUsed.begin(), gltf.extensionsUsed.end(), "KHR_mesh_quantization") !=
                  gltf.extensionsUsed.end();
    L.decodedViews = decodeMeshoptViews(path, gltf, json);
    const std::vector<int> parent = checkHierarchy(L);
    const std::vector<int> roots = sceneRoots(L, parent);
    checkMemoryNeeds(L, roots);
    convertMaterials(L);
    // What the file holds that penumbra does not use, once each (the scene file's camera is
    // the one rendered).
    if (!gltf.cameras.empty())
      L.warn(std::to_string(gltf.cameras.size()) + " camera(s) not used (the scene's camera renders)");
    for (const std::string& e : gltf.extensionsUsed)
      if (std::find(std::begin(kGltfExtensions), std::end(kGltfExtensions), e) == std::end(kGltfExtensions))
        L.warn("extension " + e + " is not read");
    std::size_t colours = 0;
    for (const tinygltf::Mesh& mesh : gltf.meshes)
      for (const tinygltf::Primitive& p : mesh.primitives) colours += p.attributes.count("COLOR_0");
    if (colours) L.warn(std::to_string(colours) + " primitive(s) with COLOR_0: vertex colours are not used");
    if (!gltf.skins.empty() || !gltf.animations.empty()) {
      L.warn("skins and animations ignored: nodes are placed by their static transforms");
    }

    std::map<std::pair<int, int>, Primitive> primitives;  // (mesh, primitive) -> converted
    std::size_t dropped = 0;
    // Iterative traversal: a deep chain of nodes must not exhaust the stack.
    std::vector<std::pair<int, glm::dmat4>> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, glm::dmat4(1.0)});
    while (!stack.empty()) {
      const auto [index, parentWorld] = stack.back();
      stack.pop_back();
      const tinygltf::Node& node = gltf.nodes[std::size_t(index)];
      const std::string label = "node " + std::to_string(index) + (node.name.empty() ? "" : " '" + node.name + "'");
      const glm::dmat4 world = parentWorld * localMatrix(node);
      if (!usable(world)) {
        L.warn(label + ": singular or non-finite transform; node and its children dropped");
        ++dropped;
        continue;
      }
      for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.push_back({*c, world});
      nodeLights(L, std::size_t(index), world, label);
      if (node.mesh < 0) continue;
      if (std::size_t(node.mesh) >= gltf.meshes.size()) {
        L.fail(label + ": mesh " + std::to_string(node.mesh) + " does not exist");
      }
      const tinygltf::Mesh& mesh = gltf.meshes[std::size_t(node.mesh)];
      for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
        const std::string name = L.file + "#" + (mesh.name.empty() ? "mesh " + std::to_string(node.mesh) : mesh.name) +
                                 (mesh.primitives.size() > 1 ? "/" + std::to_string(p) : "");
        const auto key = std::make_pair(node.mesh, int(p));
        auto it = primitives.find(key);
        if (it == primitives.end()) {
          it = primitives.emplace(key, convertPrimitive(L, mesh.primitives[p], name)).first;
        }
        if (it->second.skipped || it->second.mesh.triangles.empty()) continue;
        SceneMesh sm;
        sm.name = name + (node.name.empty() ? "" : "@" + node.name);
        sm.mesh = it->second.mesh;
        sm.report = it->second.report;
        sm.material = it->second.material;
        if (const std::size_t n = placeMesh(sm.mesh, sm.report, glm::mat4(world))) {
          L.warn(label + ": " + std::to_string(n) + " triangles of " + name +
                 " dropped: the node's transform takes them beyond float range");
        }
        out.meshes.push_back(std::move(sm));
      }
    }
    const std::string summary = L.dropSummary();
    if (out.meshes.empty() && out.lights.empty()) {
      std::string why;
      if (!summary.empty()) why += "triangles dropped: " + summary;
      if (dropped) why += (why.empty() ? "" : "; ") + std::to_string(dropped) + " nodes dropped";
      if (L.primitivesSkipped) {
        why += (why.empty() ? "" : "; ") + std::to_string(L.primitivesSkipped) +
               " primitives without triangles (points, lines, no POSITION or sparse)";
      }
      if (roots.empty()) why += (why.empty() ? "" : "; ") + std::string("the scene has no nodes");
      L.fail("no triangles to load" + (why.empty() ? std::string() : " (" + why + ")"));
    }
    if (!summary.empty()) {
      L.warn("triangles dropped in " + std::to_string(L.primitivesWithDrops) + " of " +
             std::to_string(primitives.size()) + " primitives: " + summary);
    }
  } catch (const Json::exception& e) {
    throw Error(path, std::string("malformed glTF: ") + e.what());
  }
  return out;
}

}  // namespace penumbra::detail
