// Scene queries, procedural shapes, file references and the loadScene() entry point.
#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <sstream>

#include "core/error.h"
#include "core/image_io.h"
#include "scene/loaders.h"

namespace penumbra {

namespace fs = std::filesystem;
using detail::Json;

float Light::area() const {
  switch (shape) {
    case LightShape::Rect:
      return size.x * size.y;
    case LightShape::Disk:
      return glm::pi<float>() * size.x * size.x;
    case LightShape::Sphere:
      return 4.0f * glm::pi<float>() * size.x * size.x;
    case LightShape::Point:
      return 0.0f;
  }
  return 0.0f;
}

float Light::penumbraHalfSize() const {
  switch (shape) {
    case LightShape::Rect:
    case LightShape::Disk:
      return 0.5f * std::sqrt(area());
    case LightShape::Sphere:
      return 0.5f * std::sqrt(glm::pi<float>()) * size.x;
    case LightShape::Point:
      return 0.0f;
  }
  return 0.0f;
}

int Light::frameAt(float time) const {
  if (emissionFrames.empty()) return -1;
  const int n = int(emissionFrames.size());
  if (n == 1 || !(fps > 0.0f) || !std::isfinite(time)) return 0;
  // Negative times wrap too, so an animation can be sampled around t = 0.
  const double frame = std::floor(double(time) * double(fps));
  const double wrapped = frame - double(n) * std::floor(frame / double(n));
  return std::clamp(int(wrapped), 0, n - 1);
}

std::size_t Scene::triangleCount() const {
  std::size_t n = 0;
  for (const SceneMesh& m : meshes) n += m.mesh.triangles.size();
  return n;
}

bool Scene::alphaTested(int index) const {
  if (index < 0 || std::size_t(index) >= materials.size()) return false;
  const Material& m = materials[std::size_t(index)];
  if (m.alphaMode != AlphaMode::Mask || !(m.opacity >= 1.0f) || m.baseColorTexture < 0 ||
      std::size_t(m.baseColorTexture) >= textures.size())
    return false;
  const Image& image = textures[std::size_t(m.baseColorTexture)].image;
  if (image.channels != 4) return false;
  for (std::size_t i = 0; i < image.pixelCount(); ++i)
    if (image.data[i * 4 + 3] * m.alphaFactor < m.alphaCutoff) return true;
  return false;
}

bool Scene::hasAlphaTested() const {
  for (const SceneMesh& m : meshes)
    if (!m.mesh.triangles.empty() && alphaTested(m.material)) return true;
  return false;
}

bool Scene::hasSemiOpaque() const {
  for (const SceneMesh& m : meshes) {
    if (m.material < 0 || std::size_t(m.material) >= materials.size()) continue;
    const float o = materials[std::size_t(m.material)].opacity;
    if (o > 0.0f && o < 1.0f && !m.mesh.triangles.empty()) return true;
  }
  return false;
}

glm::vec3 Scene::extent() const {
  glm::vec3 lo, hi;
  bounds(lo, hi);
  return glm::max(glm::abs(lo), glm::abs(hi));
}

glm::mat4 Spin::at(float time) const {
  const glm::mat4 toPivot = glm::translate(glm::mat4(1.0f), pivot);
  return toPivot * glm::rotate(glm::mat4(1.0f), glm::radians(degreesPerSecond * time), axis) *
         glm::translate(glm::mat4(1.0f), -pivot);
}

void Scene::makeCameraRelative() {
  const glm::vec3 c = camera.position;
  if (c == glm::vec3(0.0f)) return;
  for (SceneMesh& m : meshes) {
    for (glm::vec3& p : m.mesh.positions) p -= c;
    m.spin.pivot -= c;
  }
  for (Light& l : lights) {
    l.position -= c;
    l.spin.pivot -= c;
  }
  camera.target -= c;
  camera.position = glm::vec3(0.0f);
  origin += glm::dvec3(c);
}

bool Scene::isAnimated() const {
  return std::any_of(meshes.begin(), meshes.end(), [](const SceneMesh& m) { return m.spin.active(); }) ||
         std::any_of(lights.begin(), lights.end(), [](const Light& l) { return l.spin.active(); });
}

Scene Scene::posedAt(float time) const {
  Scene out = *this;
  for (SceneMesh& m : out.meshes)
    if (m.spin.active()) detail::transformMesh(m.mesh, m.spin.at(time));
  for (Light& l : out.lights)
    if (l.spin.active()) l = detail::transformLight(l, l.spin.at(time));  // keeps the spin
  return out;
}

void Scene::bounds(glm::vec3& lo, glm::vec3& hi) const {
  // Only vertices that triangles use: cleaning keeps the vertex arrays, so dropped NaN or
  // stray vertices would otherwise leak into the bounds.
  lo = glm::vec3(std::numeric_limits<float>::max());
  hi = glm::vec3(-std::numeric_limits<float>::max());
  bool any = false;
  for (const SceneMesh& m : meshes) {
    const auto& p = m.mesh.positions;
    for (const glm::uvec3& t : m.mesh.triangles) {
      for (int k = 0; k < 3; ++k) {
        if (t[k] >= p.size()) continue;
        const glm::vec3 v = p[t[k]];
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) continue;
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
        any = true;
      }
    }
  }
  if (!any) lo = hi = glm::vec3(0.0f);
}

namespace detail {

// ---------------------------------------------------------------------------------------------
// Procedural shapes

geo::TriangleMesh makeBox(glm::vec3 size) {
  geo::TriangleMesh m;
  const glm::vec3 h = 0.5f * size;
  // Corner i has sign bits x=1, y=2, z=4; sharing the 8 corners makes the box closed.
  for (int i = 0; i < 8; ++i) {
    m.positions.push_back({(i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y, (i & 4) ? h.z : -h.z});
  }
  auto corner = [](glm::ivec3 s) { return std::uint32_t((s.x > 0 ? 1 : 0) | (s.y > 0 ? 2 : 0) | (s.z > 0 ? 4 : 0)); };
  // Each face: outward normal n and in-plane axes u, v with u x v = n, so the corner order
  // (-u,-v), (+u,-v), (+u,+v), (-u,+v) is counter-clockwise seen from outside.
  const glm::ivec3 faces[6][3] = {
      {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},  {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}}, {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}},
      {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}, {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}},
  };
  for (const auto& f : faces) {
    const glm::ivec3 n = f[0], u = f[1], v = f[2];
    const std::uint32_t c0 = corner(n - u - v), c1 = corner(n + u - v);
    const std::uint32_t c2 = corner(n + u + v), c3 = corner(n - u + v);
    m.triangles.push_back({c0, c1, c2});
    m.triangles.push_back({c0, c2, c3});
  }
  return m;
}

geo::TriangleMesh makeSphere(float radius, int segments, int rings) {
  geo::TriangleMesh m;
  const float pi = glm::pi<float>();
  m.positions.push_back({0.0f, radius, 0.0f});  // north pole
  for (int i = 1; i < rings; ++i) {
    const float theta = pi * float(i) / float(rings);
    const float y = radius * std::cos(theta), rho = radius * std::sin(theta);
    for (int j = 0; j < segments; ++j) {
      const float phi = 2.0f * pi * float(j) / float(segments);
      m.positions.push_back({rho * std::cos(phi), y, rho * std::sin(phi)});
    }
  }
  m.positions.push_back({0.0f, -radius, 0.0f});  // south pole
  const std::uint32_t south = std::uint32_t(m.positions.size() - 1);
  auto ring = [&](int i, int j) { return std::uint32_t(1 + (i - 1) * segments + (j % segments)); };
  // With x = cos(phi), z = sin(phi), phi grows to the left seen from outside, so a band quad
  // (lower-right, upper-right, upper-left, lower-left) is (b_j, a_j, a_j+1, b_j+1).
  for (int j = 0; j < segments; ++j) {
    m.triangles.push_back({ring(1, j), 0u, ring(1, j + 1)});
    for (int i = 1; i + 1 < rings; ++i) {
      const std::uint32_t a0 = ring(i, j), a1 = ring(i, j + 1);
      const std::uint32_t b0 = ring(i + 1, j), b1 = ring(i + 1, j + 1);
      m.triangles.push_back({b0, a0, a1});
      m.triangles.push_back({b0, a1, b1});
    }
    m.triangles.push_back({south, ring(rings - 1, j), ring(rings - 1, j + 1)});
  }
  for (const glm::vec3& p : m.positions) m.normals.push_back(glm::normalize(p));
  return m;
}

geo::TriangleMesh makeCylinder(float radius, float height, int segments, bool topCap, bool bottomCap) {
  geo::TriangleMesh m;
  const float pi = glm::pi<float>();
  const float h = 0.5f * height;
  for (int level = 0; level < 2; ++level) {  // 0: bottom ring, 1: top ring
    for (int j = 0; j < segments; ++j) {
      const float phi = 2.0f * pi * float(j) / float(segments);
      m.positions.push_back({radius * std::cos(phi), level ? h : -h, radius * std::sin(phi)});
    }
  }
  auto bottom = [&](int j) { return std::uint32_t(j % segments); };
  auto top = [&](int j) { return std::uint32_t(segments + j % segments); };
  for (int j = 0; j < segments; ++j) {
    m.triangles.push_back({bottom(j), top(j), top(j + 1)});
    m.triangles.push_back({bottom(j), top(j + 1), bottom(j + 1)});
  }
  if (topCap) {
    m.positions.push_back({0.0f, h, 0.0f});
    const std::uint32_t c = std::uint32_t(m.positions.size() - 1);
    for (int j = 0; j < segments; ++j) m.triangles.push_back({c, top(j + 1), top(j)});
  }
  if (bottomCap) {
    m.positions.push_back({0.0f, -h, 0.0f});
    const std::uint32_t c = std::uint32_t(m.positions.size() - 1);
    for (int j = 0; j < segments; ++j) m.triangles.push_back({c, bottom(j), bottom(j + 1)});
  }
  return m;
}

geo::TriangleMesh makeQuad(glm::vec2 size) {
  const float w = 0.5f * size.x, d = 0.5f * size.y;
  const glm::vec3 corners[4] = {{-w, 0, -d}, {-w, 0, d}, {w, 0, d}, {w, 0, -d}};
  geo::TriangleMesh m = makeQuad(corners);
  m.uvs = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
  return m;
}

geo::TriangleMesh makeQuad(const glm::vec3 corners[4]) {
  geo::TriangleMesh m;
  m.positions.assign(corners, corners + 4);
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

geo::TriangleMesh makeDisk(float radius, int segments) {
  geo::TriangleMesh m;
  const float pi = glm::pi<float>();
  m.positions.push_back({0.0f, 0.0f, 0.0f});
  m.uvs.push_back({0.5f, 0.5f});
  for (int j = 0; j < segments; ++j) {
    const float phi = 2.0f * pi * float(j) / float(segments);
    const float c = std::cos(phi), s = std::sin(phi);
    m.positions.push_back({radius * c, 0.0f, radius * s});
    m.uvs.push_back({0.5f + 0.5f * c, 0.5f + 0.5f * s});
  }
  for (int j = 0; j < segments; ++j) {
    m.triangles.push_back({0u, std::uint32_t(1 + (j + 1) % segments), std::uint32_t(1 + j)});
  }
  return m;
}

void transformMesh(geo::TriangleMesh& mesh, const glm::mat4& m) {
  const glm::mat3 linear(m);
  const glm::mat3 normalFromLocal = glm::transpose(glm::inverse(linear));
  for (glm::vec3& p : mesh.positions) p = glm::vec3(m * glm::vec4(p, 1.0f));
  for (glm::vec3& n : mesh.normals) {
    const glm::vec3 t = normalFromLocal * n;
    const float len = glm::length(t);
    n = len > 0.0f ? t / len : n;
  }
  if (glm::determinant(linear) < 0.0f) {
    for (glm::uvec3& t : mesh.triangles) std::swap(t.y, t.z);
  }
}

std::size_t placeMesh(geo::TriangleMesh& mesh, geo::MeshReport& report, const glm::mat4& m) {
  transformMesh(mesh, m);
  const auto finite = [](const glm::vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); };
  bool allFinite = true;
  for (const glm::uvec3& t : mesh.triangles)
    allFinite = allFinite && finite(mesh.positions[t.x]) && finite(mesh.positions[t.y]) && finite(mesh.positions[t.z]);
  if (allFinite) return 0;  // the common case: the report of the cleaned mesh still holds
  const std::size_t before = report.droppedTotal();
  geo::cleanMesh(mesh, report);
  return report.droppedTotal() - before;
}

Light transformLight(const Light& light, const glm::mat4& m) {
  Light out = light;
  const glm::mat3 linear(m);
  out.position = glm::vec3(m * glm::vec4(light.position, 1.0f));
  if (light.shape == LightShape::Point) return out;
  const glm::vec3 t = linear * light.tangent;
  const glm::vec3 b = linear * light.bitangent();
  glm::vec3 n = glm::transpose(glm::inverse(linear)) * light.normal;
  const float tl = glm::length(t), bl = glm::length(b), nl = glm::length(n);
  if (!(tl > 0.0f) || !(bl > 0.0f) || !(nl > 0.0f)) return out;  // singular: caller validates
  n /= nl;
  out.normal = n;
  out.tangent = glm::normalize(t - glm::dot(t, n) * n);
  if (light.shape == LightShape::Rect) {
    out.size = {light.size.x * tl, light.size.y * bl};
  } else {
    out.size.x = light.size.x * std::sqrt(tl * bl);
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Paths

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

bool isGeometryExtension(const std::string& ext) {
  return ext == ".gltf" || ext == ".glb" || ext == ".obj" || ext == ".ply" || ext == ".off" || ext == ".stl";
}

std::string relativePathProblem(const std::string& path) {
  if (path.empty()) return "is empty";
  for (unsigned char c : path) {
    if (c < 0x20 || c == 0x7f) return "contains a control character";
    if (std::string_view("\\$`;|&<>*?!{}[]()~'\"#%").find(char(c)) != std::string_view::npos) {
      return std::string("contains the shell metacharacter '") + char(c) + "'";
    }
  }
  // A scheme ("http:", "file:", "C:") is letters followed by ':' before any '/'.
  const std::size_t colon = path.find(':');
  if (colon != std::string::npos && path.find('/') > colon) {
    return "is a URI with scheme '" + path.substr(0, colon) + ":', not a relative path";
  }
  if (path.find(':') != std::string::npos) return "contains ':'";
  if (path.front() == '/') return "is an absolute path";
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t end = std::min(path.find('/', start), path.size());
    if (path.compare(start, end - start, "..") == 0 && end - start == 2) {
      return "leaves its folder ('..')";
    }
    start = end + 1;
  }
  return {};
}

bool isInsideFolder(const std::string& path, const std::string& folder) {
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(fs::path(path), ec);
  if (ec) return false;
  const fs::path f = fs::weakly_canonical(fs::path(folder.empty() ? "." : folder), ec);
  if (ec) return false;
  auto pi = p.begin();
  for (auto fi = f.begin(); fi != f.end(); ++fi, ++pi) {
    if (fi->empty()) continue;  // trailing separator
    if (pi == p.end() || *pi != *fi) return false;
  }
  return true;
}

std::string resolveSceneReference(const std::string& reference, const std::string& baseDir, const std::string& where,
                                  const std::string& context) {
  static const std::string kAssimpPrefix = "assimp:";
  static const std::string kAssimpRoot = "/usr/share/assimp/models";
  std::string root = baseDir.empty() ? "." : baseDir;
  std::string relative = reference;
  if (reference.rfind(kAssimpPrefix, 0) == 0) {
    relative = reference.substr(kAssimpPrefix.size());
    root = kAssimpRoot;
    if (!fs::is_directory(root)) {
      throw Error(where, context + ": '" + reference +
                             "' needs the Debian package "
                             "assimp-testmodels (" +
                             kAssimpRoot + " is missing)");
    }
  }
  if (std::string why = relativePathProblem(relative); !why.empty()) {
    throw Error(where,
                context + ": path '" + reference + "' " + why + " (paths are relative to the scene file's folder)");
  }
  const std::string resolved = (fs::path(root) / relative).lexically_normal().string();
  if (const std::string why = fileProblem(resolved); !why.empty()) {
    throw Error(where,
                context + ": '" + reference + "' " +
                    (why == "no such file" ? "not found (looked for " + resolved + ")" : "(" + resolved + ") " + why));
  }
  if (!isInsideFolder(resolved, root)) {
    throw Error(where, context + ": '" + reference + "' resolves outside " + root);
  }
  return resolved;
}

Texture readTextureFile(const std::string& path, std::vector<std::string>& warnings, const LoadOptions& options) {
  Texture t;
  t.source = path;
  if (!options.decodeTextures) {
    const ImageHeader header = readImageHeader(path);
    t.width = header.width, t.height = header.height;
    return t;
  }
  if (lowerExtension(path) == ".exr") {
    // NaN/Inf texels are replaced by 0; the scene's warnings say how many, as `penumbra info`
    // prints them (hard-cases.md, bad inputs: EXR textures "sanitised with a warning").
    int sanitized = 0;
    t.image = readExr(path, &sanitized);
    if (sanitized > 0)
      warnings.push_back(path + ": replaced " + std::to_string(sanitized) + " non-finite texels with 0");
  } else {
    t.image = readTexture(path, /*srgb=*/true);
  }
  t.width = t.image.width, t.height = t.image.height;
  return t;
}

Model loadGeometryFile(const std::string& path, const LoadOptions& options) {
  const std::string ext = lowerExtension(path);
  if (ext == ".gltf" || ext == ".glb") return loadGltf(path, options);
  if (ext == ".obj") return loadObjModel(path, options);
  if (!isGeometryExtension(ext)) {
    throw Error(path, "unsupported geometry format '" + ext + "' (expected .gltf, .glb, .obj, .ply, .off or .stl)");
  }
  Model model;
  SceneMesh sm;
  sm.name = path;
  sm.mesh = geo::loadMeshFile(path, sm.report);
  sm.material = -1;
  // Vertices copied for the silhouette mesh change nothing loaded: counted, not warned.
  if (sm.report.worthWarning()) {
    model.warnings.push_back(path + ": " + sm.report.summary());
  }
  model.meshes.push_back(std::move(sm));
  return model;
}

}  // namespace detail

namespace {

std::string readTextFile(const std::string& path) {
  if (const std::string why = fileProblem(path); !why.empty()) throw Error(path, why);
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (ec) throw Error(path, "cannot read: " + ec.message());
  if (size > (64u << 20)) throw Error(path, "scene file larger than 64 MiB");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string folderOf(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

}  // namespace

Scene loadScene(const std::string& path, const std::vector<std::string>& overrides, const LoadOptions& options) {
  const std::string ext = detail::lowerExtension(path);
  const std::string stem = fs::path(path).stem().string();
  Json doc;
  if (ext == ".json") {
    const std::string text = readTextFile(path);
    doc = detail::parseJsonDocument(text, path);
    if (!doc.is_object()) throw Error(path, "a scene file must hold a JSON object");
    if (!doc.contains("name")) doc["name"] = stem;
  } else if (detail::isGeometryExtension(ext)) {
    if (const std::string why = fileProblem(path); !why.empty()) throw Error(path, why);
    // Loaded once here for its bounds; interpretScene loads it again, which keeps a single
    // code path for placement (bare files are small compared with the cost of rendering).
    detail::Model model = detail::loadGeometryFile(path, LoadOptions{/*decodeTextures=*/false});
    Scene probe;
    for (SceneMesh& m : model.meshes) probe.meshes.push_back(std::move(m));
    glm::vec3 lo, hi;
    probe.bounds(lo, hi);
    doc = detail::bareGeometryDocument(fs::path(path).filename().string(), lo, hi);
    doc["name"] = stem;
  } else {
    throw Error(path, "unsupported scene file '" + ext + "' (expected .json, .gltf, .glb, .obj, .ply, .off or .stl)");
  }
  detail::applyOverrides(doc, overrides);
  Scene scene = detail::interpretScene(doc, path, folderOf(path), options);
  scene.sourcePath = path;
  return scene;
}

Scene defaultScene(const std::vector<std::string>& overrides, const LoadOptions& options) {
  Json doc = detail::defaultSceneDocument();
  detail::applyOverrides(doc, overrides);
  // File references added by overrides resolve against the working directory.
  Scene scene = detail::interpretScene(doc, "<default scene>", ".", options);
  scene.sourcePath.clear();
  return scene;
}

}  // namespace penumbra
