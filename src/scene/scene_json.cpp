// The scene description interpreter (overrides: overrides.cpp). The format is documented in
// docs/scene-format.md; every key read here is listed there.
#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <map>
#include <memory>
#include <set>

#include "core/error.h"
#include "core/image_io.h"
#include "core/key_values.h"
#include "core/memory.h"
#include "core/log.h"
#include "scene/loaders.h"

namespace penumbra::detail {

namespace {

constexpr const char* kProceduralPrefix = "procedural:";
constexpr int kMaxSegments = 4096;
constexpr int kMaxResolution = 16384;

struct Context {
  std::string where;
  std::string baseDir;
  Scene& scene;
  LoadOptions options;
  std::map<std::string, int> materialByName;
  std::map<std::string, int> textureByKey;  // resolved path or procedural name
  std::map<std::pair<int, float>, int> opacityVariants;
  struct Placed {
    std::shared_ptr<const Model> model;
    int materialBase = 0;
    int textureBase = 0;
  };
  std::map<std::string, Placed> models;  // by resolved path

  void warn(const std::string& message) {
    scene.warnings.push_back(message);
    PLOG_WARN("{}", message);
  }
  [[noreturn]] void fail(const std::string& context, const std::string& what) const {
    throw Error(where, context.empty() ? what : context + ": " + what);
  }
};

// A JSON scalar as the shared key/value reader sees it (core/key_values.h).
KeyValue keyValueOf(const Json& v) {
  KeyValue k;
  k.shown = shownJson(v);
  if (v.is_number_integer())
    k.kind = KeyValue::Kind::Integer, k.number = v.get<double>();
  else if (v.is_number())
    k.kind = KeyValue::Kind::Number, k.number = v.get<double>();
  else if (v.is_boolean())
    k.kind = KeyValue::Kind::Boolean, k.boolean = v.get<bool>();
  else if (v.is_string())
    k.kind = KeyValue::Kind::String, k.text = v.get<std::string>();
  return k;
}

// One JSON object being interpreted, its values converted and checked by the reader technique
// parameters use too (core/key_values.h). Keys read through it are marked used; finish() warns
// about the rest so that a misspelt key is never silently ignored.
class Fields {
 public:
  Fields(Context& ctx, const Json& object, std::string context)
      : ctx_(ctx), object_(object), context_(std::move(context)) {
    if (!object_.is_object()) ctx_.fail(context_, "expected a JSON object");
  }

  const std::string& context() const { return context_; }
  std::string at(const std::string& key) const { return context_ + "." + key; }
  bool has(const std::string& key) const { return object_.contains(key); }

  const Json* get(const std::string& key) {
    used_.insert(key);
    const auto it = object_.find(key);
    return it == object_.end() ? nullptr : &*it;
  }

  float number(const std::string& key, float fallback) {
    const Json* v = get(key);
    return v ? toFloat(*v, at(key)) : fallback;
  }
  float positive(const std::string& key, float fallback) {
    const float x = number(key, fallback);
    if (!(x > 0.0f)) ctx_.fail(at(key), "must be positive, got " + fmtFloat(x));
    return x;
  }
  int integer(const std::string& key, int fallback, int lo, int hi) {
    const Json* v = get(key);
    return v ? readInteger(keyValueOf(*v), place(at(key)), lo, hi) : fallback;
  }
  bool boolean(const std::string& key, bool fallback) {
    const Json* v = get(key);
    return v ? readBoolean(keyValueOf(*v), place(at(key))) : fallback;
  }
  std::string string(const std::string& key, const std::string& fallback) {
    const Json* v = get(key);
    return v ? readString(keyValueOf(*v), place(at(key))) : fallback;
  }
  glm::vec3 vec3(const std::string& key, glm::vec3 fallback) {
    const Json* v = get(key);
    return v ? toVec(*v, at(key), 3) : fallback;
  }
  // A number (all components) or an array of n numbers.
  glm::vec3 scalarOrVec(const std::string& key, glm::vec3 fallback, int n) {
    const Json* v = get(key);
    if (!v) return fallback;
    if (v->is_number()) return glm::vec3(toFloat(*v, at(key)));
    return toVec(*v, at(key), n);
  }

  void finish() {
    for (const auto& item : object_.items()) {
      if (used_.count(item.key())) continue;
      ctx_.warn(ctx_.where + ": " + context_ + ": unknown key '" + item.key() + "' ignored");
    }
  }

  float toFloat(const Json& v, const std::string& context) const {
    const KeyValue k = keyValueOf(v);
    const double inf = std::numeric_limits<double>::infinity();
    const float x = float(readNumber(k, place(context), -inf, inf));
    if (!std::isfinite(x)) place(context).fail("not a finite number: " + k.shown);
    return x;
  }
  glm::vec3 toVec(const Json& v, const std::string& context, int n) const {
    if (!v.is_array() || int(v.size()) != n) {
      ctx_.fail(context, "expected " + std::to_string(n) + " numbers, got " + shownJson(v));
    }
    glm::vec3 out(0.0f);
    for (int i = 0; i < n; ++i) out[i] = toFloat(v[std::size_t(i)], context);
    return out;
  }
  // Shortest form that reads back as the same float ("0.5", "1e-30"; std::to_string printed
  // 1e-30 as "0.000000", which made a tiny size read as zero).
  static std::string fmtFloat(float x) { return fmt::format("{}", x); }

 private:
  KeyPlace place(const std::string& context) const { return {ctx_.where, context, ExitCode::Error}; }
  Context& ctx_;
  const Json& object_;
  std::string context_;
  std::set<std::string> used_;
};

bool isFinite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string describe(const std::string& base, int index, const std::string& name) {
  std::string s = base + "[" + std::to_string(index) + "]";
  if (!name.empty()) s += " '" + name + "'";
  return s;
}

const Json* arrayField(Fields& f, const std::string& key, Context& ctx) {
  const Json* v = f.get(key);
  if (v && !v->is_array()) ctx.fail(key, "expected an array, got " + shownJson(*v));
  return v;
}

std::string nameOf(const Json& item) {
  if (item.is_object()) {
    const auto it = item.find("name");
    if (it != item.end() && it->is_string()) return it->get<std::string>();
  }
  return {};
}

int loadTexture(Context& ctx, const std::string& reference, const std::string& context) {
  const bool procedural = reference.rfind(kProceduralPrefix, 0) == 0;
  std::string key = reference;
  if (procedural) {
    const std::string name = reference.substr(std::string(kProceduralPrefix).size());
    if (name != "stained-glass") {
      ctx.fail(context, "unknown procedural texture '" + name + "' (known: stained-glass)");
    }
  } else {
    key = resolveSceneReference(reference, ctx.baseDir, ctx.where, context);
  }
  if (const auto it = ctx.textureByKey.find(key); it != ctx.textureByKey.end()) return it->second;
  Texture texture;
  if (procedural) {
    texture.source = key;
    texture.image = stainedGlassImage(64);
    texture.width = texture.image.width;
    texture.height = texture.image.height;
  } else {
    std::vector<std::string> warnings;
    texture = readTextureFile(key, warnings, ctx.options);
    for (const std::string& w : warnings) ctx.warn(w);
  }
  const int index = int(ctx.scene.textures.size());
  ctx.scene.textures.push_back(std::move(texture));
  ctx.textureByKey[key] = index;
  return index;
}

// ---------------------------------------------------------------------------------------------

void readMaterial(Context& ctx, const Json& item, int index) {
  Fields f(ctx, item, describe("materials", index, nameOf(item)));
  Material m;
  m.name = f.string("name", "");
  if (m.name.empty()) ctx.fail(f.context(), "a material needs a \"name\"");
  if (ctx.materialByName.count(m.name)) ctx.fail(f.context(), "duplicate material name");
  m.baseColor = f.scalarOrVec("baseColor", m.baseColor, 3);
  if (glm::any(glm::lessThan(m.baseColor, glm::vec3(0.0f)))) {
    ctx.fail(f.at("baseColor"), "components must be >= 0");
  }
  if (f.has("texture")) m.baseColorTexture = loadTexture(ctx, f.string("texture", ""), f.at("texture"));
  m.opacity = f.number("opacity", 1.0f);
  if (m.opacity < 0.0f || m.opacity > 1.0f) {
    ctx.fail(f.at("opacity"), "must be in [0, 1], got " + Fields::fmtFloat(m.opacity));
  }
  m.alphaMode = m.opacity < 1.0f ? AlphaMode::Blend : AlphaMode::Opaque;
  // glTF's alphaMode MASK: the texture's alpha cuts holes (alpha-tested occluders).
  if (f.has("alphaCutoff")) {
    m.alphaCutoff = f.number("alphaCutoff", 0.5f);
    if (!(m.alphaCutoff > 0.0f && m.alphaCutoff <= 1.0f))
      ctx.fail(f.at("alphaCutoff"), "must be in (0, 1], got " + Fields::fmtFloat(m.alphaCutoff));
    if (m.baseColorTexture < 0) ctx.fail(f.at("alphaCutoff"), "needs a \"texture\" whose alpha it tests");
    if (m.opacity < 1.0f) ctx.fail(f.at("alphaCutoff"), "and \"opacity\" below 1 exclude each other");
    m.alphaMode = AlphaMode::Mask;
  }
  // Either key selects the glTF metallic-roughness BRDF (defaults: a rough dielectric).
  if (f.has("metallic") || f.has("roughness")) {
    m.brdf = BrdfModel::MetallicRoughness;
    m.metallic = f.number("metallic", 0.0f);
    m.roughness = f.number("roughness", 1.0f);
    for (const char* key : {"metallic", "roughness"}) {
      const float v = std::string(key) == "metallic" ? m.metallic : m.roughness;
      if (f.has(key) && !(v >= 0.0f && v <= 1.0f)) ctx.fail(f.at(key), "must be in [0, 1], got " + Fields::fmtFloat(v));
    }
  }
  f.finish();
  ctx.materialByName[m.name] = int(ctx.scene.materials.size());
  ctx.scene.materials.push_back(std::move(m));
}

// A rotation by `degrees` about the unit `axis`; cos and sin exact at multiples of 90 degrees
// (glm::radians(180) has sin 8.7e-8: a ceiling turned over lay 2e-7 off its plane, and a light
// placed on it lay behind it within rounding, which dcs must refuse).
glm::mat4 rotationDegrees(float degrees, const glm::vec3& axis) {
  const double turns = double(degrees) / 90.0;
  if (turns != std::nearbyint(turns)) return glm::rotate(glm::mat4(1.0f), glm::radians(degrees), axis);
  const int quarter = int(std::fmod(std::fmod(turns, 4.0) + 4.0, 4.0));
  const float c = quarter == 0   ? 1.0f
                  : quarter == 2 ? -1.0f
                                 : 0.0f,
              s = quarter == 1   ? 1.0f
                  : quarter == 3 ? -1.0f
                                 : 0.0f;
  // Rodrigues, as glm::rotate: R = c I + s [a]x + (1 - c) a a^T.
  glm::mat4 r(1.0f);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) r[j][i] = (1.0f - c) * axis[i] * axis[j] + (i == j ? c : 0.0f);
  r[1][0] -= s * axis.z, r[2][0] += s * axis.y;
  r[0][1] += s * axis.z, r[2][1] -= s * axis.x;
  r[0][2] -= s * axis.y, r[1][2] += s * axis.x;
  return r;
}

glm::mat4 readTransform(Context& ctx, Fields& f) {
  glm::mat4 matrix(1.0f);
  if (const Json* v = f.get("matrix")) {
    if (!v->is_array() || v->size() != 16) {
      ctx.fail(f.at("matrix"), "expected 16 numbers (column-major)");
    }
    float values[16];
    for (std::size_t i = 0; i < 16; ++i) values[i] = f.toFloat((*v)[i], f.at("matrix"));
    matrix = glm::make_mat4(values);
  }
  glm::vec3 scale = f.scalarOrVec("scale", glm::vec3(1.0f), 3);
  glm::mat4 rotation(1.0f);
  if (const Json* v = f.get("rotate")) {
    if (v->is_object()) {
      Fields r(ctx, *v, f.at("rotate"));
      const glm::vec3 axis = r.vec3("axis", glm::vec3(0.0f, 1.0f, 0.0f));
      const float angle = r.number("angle", 0.0f);
      r.finish();
      if (!(glm::length(axis) > 0.0f)) ctx.fail(f.at("rotate.axis"), "must not be zero");
      rotation = rotationDegrees(angle, glm::normalize(axis));
    } else {
      const glm::vec3 deg = f.toVec(*v, f.at("rotate"), 3);
      // Degrees about X, then Y, then Z (R = Rz Ry Rx).
      rotation =
          rotationDegrees(deg.z, {0, 0, 1}) * rotationDegrees(deg.y, {0, 1, 0}) * rotationDegrees(deg.x, {1, 0, 0});
    }
  }
  const glm::vec3 translate = f.vec3("translate", glm::vec3(0.0f));
  const glm::mat4 world =
      glm::translate(glm::mat4(1.0f), translate) * rotation * glm::scale(glm::mat4(1.0f), scale) * matrix;
  const float det = glm::determinant(glm::mat3(world));
  if (!std::isfinite(det) || std::abs(det) < 1e-24f) {
    ctx.fail(f.context(), "the transform is singular (zero scale or degenerate matrix)");
  }
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      if (!std::isfinite(world[c][r])) ctx.fail(f.context(), "the transform is not finite");
    }
  }
  return world;
}

glm::vec3 unitOrFail(Context& ctx, glm::vec3 v, const std::string& context);

// "spin": {"axis": [0, 1, 0], "degreesPerSecond": 30, "pivot": [x, y, z]} (for --frames).
Spin readSpin(Context& ctx, Fields& f, glm::vec3 defaultPivot) {
  Spin spin;
  const Json* v = f.get("spin");
  if (!v) return spin;
  if (!v->is_object()) ctx.fail(f.at("spin"), "expected {\"axis\", \"degreesPerSecond\", \"pivot\"}");
  Fields r(ctx, *v, f.at("spin"));
  spin.axis = unitOrFail(ctx, r.vec3("axis", spin.axis), f.at("spin.axis"));
  spin.degreesPerSecond = r.number("degreesPerSecond", 0.0f);
  spin.pivot = r.vec3("pivot", defaultPivot);
  r.finish();
  return spin;
}

geo::TriangleMesh readShape(Context& ctx, Fields& f, const std::string& shape) {
  auto segments = [&](int fallback) { return f.integer("segments", fallback, 3, kMaxSegments); };
  // Sizes of 0, -0 or below: the shape vanished without a word (a sphere's radius was refused).
  auto size = [&](glm::vec3 fallback, int n) {
    const glm::vec3 v = f.scalarOrVec("size", fallback, n);
    for (int k = 0; k < n; ++k)
      if (!(v[k] > 0.0f)) ctx.fail(f.at("size"), "must be positive, got " + Fields::fmtFloat(v[k]));
    return v;
  };
  if (shape == "box") return makeBox(size(glm::vec3(1.0f), 3));
  if (shape == "plane" || shape == "quad") {
    if (shape == "quad" && f.has("corners")) {
      const Json* v = f.get("corners");
      if (!v->is_array() || v->size() != 4) ctx.fail(f.at("corners"), "expected 4 points");
      glm::vec3 corners[4];
      for (std::size_t i = 0; i < 4; ++i) corners[i] = f.toVec((*v)[i], f.at("corners"), 3);
      return makeQuad(corners);
    }
    return makeQuad(glm::vec2(size(glm::vec3(shape == "plane" ? 10.0f : 1.0f), 2)));
  }
  // Memory before allocating: the triangle count is known from the parameters, so a shape
  // this process cannot hold is refused before it is built (4096 x 4096 segments: 33.5 M
  // triangles, 5.4 GiB to build and clean).
  auto fits = [&](double triangles, const std::string& what) {
    checkMemory(
        ctx.where,
        f.context() + ": " + shape + " of " + what + " (" + fmt::format("{:.1f} M triangles", triangles / 1e6) + ")",
        triangles * kCleanBytesPerTriangle);
  };
  if (shape == "sphere") {
    const float radius = f.positive("radius", 0.5f);
    const int seg = segments(32);
    const int rings = f.integer("rings", std::max(2, seg / 2), 2, kMaxSegments);
    fits(2.0 * seg * (rings - 1), fmt::format("{} x {} segments", seg, rings));
    return makeSphere(radius, seg, rings);
  }
  if (shape == "cylinder") {
    const float radius = f.positive("radius", 0.5f);
    const float height = f.positive("height", 1.0f);
    const int seg = segments(32);
    const std::string caps = f.string("caps", "both");
    if (caps != "both" && caps != "top" && caps != "bottom" && caps != "none") {
      ctx.fail(f.at("caps"), "expected \"both\", \"top\", \"bottom\" or \"none\", got '" + caps + "'");
    }
    bool top = caps == "both" || caps == "top", bottom = caps == "both" || caps == "bottom";
    if (f.boolean("open_bottom", false)) bottom = false;
    return makeCylinder(radius, height, seg, top, bottom);
  }
  if (shape == "disk") {
    const float radius = f.positive("radius", 0.5f);
    return makeDisk(radius, segments(32));
  }
  ctx.fail(f.at("shape"), "unknown shape '" + shape + "' (expected box, plane, quad, sphere, cylinder or disk)");
}

int withOpacity(Context& ctx, int material, float opacity) {
  const auto key = std::make_pair(material, opacity);
  if (const auto it = ctx.opacityVariants.find(key); it != ctx.opacityVariants.end()) {
    return it->second;
  }
  Material m = ctx.scene.materials[std::size_t(material)];
  m.name += "@opacity=" + Fields::fmtFloat(opacity);
  m.opacity = opacity;
  m.alphaMode = opacity < 1.0f ? AlphaMode::Blend : AlphaMode::Opaque;
  const int index = int(ctx.scene.materials.size());
  ctx.scene.materials.push_back(std::move(m));
  ctx.opacityVariants[key] = index;
  return index;
}

const Context::Placed& placeModel(Context& ctx, const std::string& path) {
  if (const auto it = ctx.models.find(path); it != ctx.models.end()) return it->second;
  auto model = std::make_shared<Model>(loadGeometryFile(path, ctx.options));
  for (SceneMesh& m : model->meshes) {
    // The file's own normals: a zero or non-finite one shades its corners with the face's
    // normal (the G-buffer's rule), said once per mesh rather than repaired in silence.
    const std::size_t bad =
        std::size_t(std::count_if(m.mesh.normals.begin(), m.mesh.normals.end(), [](const glm::vec3& n) {
          const float length = glm::length(n);
          return !(length > 0.0f) || !std::isfinite(length);
        }));
    if (bad > 0)
      ctx.warn(fmt::format(
          "{}: {} of its {} vertex normals are zero or not finite: their corners shade with the face's normal", m.name,
          bad, m.mesh.normals.size()));
    geo::ensureShadingNormals(m.mesh);  // once per file, not per instance
  }
  Context::Placed placed;
  placed.model = model;
  placed.materialBase = int(ctx.scene.materials.size());
  placed.textureBase = int(ctx.scene.textures.size());
  for (Material m : model->materials) {
    if (m.baseColorTexture >= 0) m.baseColorTexture += placed.textureBase;
    ctx.scene.materials.push_back(std::move(m));
  }
  for (const Texture& t : model->textures) ctx.scene.textures.push_back(t);
  for (const std::string& w : model->warnings) ctx.warn(w);
  return ctx.models[path] = std::move(placed);
}

void readObject(Context& ctx, const Json& item, int index) {
  const std::string name = nameOf(item);
  Fields f(ctx, item, describe("objects", index, name));
  f.string("name", "");
  int material = -1;
  if (f.has("material")) {
    const std::string m = f.string("material", "");
    const auto it = ctx.materialByName.find(m);
    if (it == ctx.materialByName.end()) {
      std::string known;
      for (const auto& [k, v] : ctx.materialByName) known += (known.empty() ? "" : ", ") + k;
      ctx.fail(f.at("material"), "unknown material '" + m + "' (" +
                                     (known.empty() ? "the scene's \"materials\" defines none" : "known: " + known) +
                                     ")");
    }
    material = it->second;
  }
  const bool hasOpacity = f.has("opacity");
  const float opacity = f.number("opacity", 1.0f);
  if (opacity < 0.0f || opacity > 1.0f) {
    ctx.fail(f.at("opacity"), "must be in [0, 1], got " + Fields::fmtFloat(opacity));
  }
  const glm::mat4 world = readTransform(ctx, f);
  const Spin spin = readSpin(ctx, f, glm::vec3(world[3]));  // pivot: the object's origin
  const std::string label = name.empty() ? "objects[" + std::to_string(index) + "]" : name;

  std::vector<SceneMesh> placed;
  if (f.has("file") && f.has("shape")) ctx.fail(f.context(), "give \"file\" or \"shape\", not both");
  if (f.has("file")) {
    const std::string path = resolveSceneReference(f.string("file", ""), ctx.baseDir, ctx.where, f.at("file"));
    const Context::Placed& model = placeModel(ctx, path);
    for (const SceneMesh& source : model.model->meshes) {
      SceneMesh m = source;
      m.name = label + "/" + source.name;
      if (const std::size_t n = placeMesh(m.mesh, m.report, world)) {
        ctx.warn(ctx.where + ": " + f.context() + ": " + std::to_string(n) + " triangles of " + source.name +
                 " dropped: the transform takes them beyond float range");
      }
      m.material = material >= 0 ? material : source.material >= 0 ? model.materialBase + source.material : 0;
      if (m.mesh.triangles.empty())
        ctx.warn(ctx.where + ": " + f.context() + ": " + source.name +
                 " has no triangle left (every one was dropped: "
                 "`penumbra info` counts why)");
      placed.push_back(std::move(m));
    }
    for (const Light& light : model.model->lights) {
      ctx.scene.lights.push_back(transformLight(light, world));
      ctx.scene.lights.back().spin = spin;
    }
  } else if (f.has("shape")) {
    SceneMesh m;
    m.name = label;
    m.mesh = readShape(ctx, f, f.string("shape", ""));
    transformMesh(m.mesh, world);
    m.report.inputVertices = m.mesh.positions.size();
    m.report.inputFaces = m.mesh.triangles.size();
    geo::cleanMesh(m.mesh, m.report);
    // A size of 1e-45, collinear quad corners, a transform that flattens the shape: triangles
    // without area in float, all dropped; the object would vanish without a word.
    if (m.mesh.triangles.empty())
      ctx.fail(f.context(), "no triangle of the " + f.string("shape", "") +
                                " has an area in float (its size, corners or "
                                "transform collapse it): all " +
                                std::to_string(m.report.inputFaces) + " dropped");
    geo::ensureShadingNormals(m.mesh);
    m.material = material >= 0 ? material : 0;
    placed.push_back(std::move(m));
  } else {
    ctx.fail(f.context(), "an object needs \"file\" or \"shape\"");
  }
  f.finish();
  for (SceneMesh& m : placed) {
    if (hasOpacity) m.material = withOpacity(ctx, m.material, opacity);
    m.spin = spin;
    ctx.scene.meshes.push_back(std::move(m));
  }
}

glm::vec3 unitOrFail(Context& ctx, glm::vec3 v, const std::string& context) {
  const float len = glm::length(v);
  if (!(len > 0.0f) || !std::isfinite(len)) ctx.fail(context, "must be a non-zero vector");
  return v / len;
}

void readLight(Context& ctx, const Json& item, int index) {
  Fields f(ctx, item, describe("lights", index, nameOf(item)));
  Light light;
  light.name = f.string("name", "light" + std::to_string(index));
  const std::string type = f.string("type", "rect");
  if (type == "rect")
    light.shape = LightShape::Rect;
  else if (type == "disk")
    light.shape = LightShape::Disk;
  else if (type == "sphere")
    light.shape = LightShape::Sphere;
  else if (type == "point")
    light.shape = LightShape::Point;
  else
    ctx.fail(f.at("type"), "unknown light type '" + type + "' (expected rect, disk, sphere or point)");

  light.position = f.vec3("position", light.position);
  light.color = f.scalarOrVec("color", light.color, 3);
  if (glm::any(glm::lessThan(light.color, glm::vec3(0.0f)))) {
    ctx.fail(f.at("color"), "components must be >= 0");
  }
  light.intensity = f.number("intensity", light.intensity);
  if (light.intensity < 0.0f) ctx.fail(f.at("intensity"), "must be >= 0");

  if (light.shape == LightShape::Rect || light.shape == LightShape::Disk) {
    if (f.has("normal") && f.has("target")) ctx.fail(f.context(), "give \"normal\" or \"target\", not both");
    if (f.has("target")) {
      light.normal = unitOrFail(ctx, f.vec3("target", {}) - light.position, f.at("target") + " (minus position)");
    } else {
      light.normal = unitOrFail(ctx, f.vec3("normal", light.normal), f.at("normal"));
    }
  }
  if (light.shape != LightShape::Point) {
    if (f.has("tangent") && f.has("up")) ctx.fail(f.context(), "give \"tangent\" or \"up\", not both");
    const glm::vec3 n = light.normal;
    glm::vec3 t;
    if (f.has("tangent")) {
      t = f.vec3("tangent", {});
    } else if (f.has("up")) {
      t = glm::cross(f.vec3("up", {}), n);  // so that bitangent = n x t follows "up"
    } else {
      t = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1);
    }
    t -= glm::dot(t, n) * n;
    light.tangent =
        unitOrFail(ctx, t, f.has("up") ? f.at("up") : f.at("tangent") + " (projected onto the light's plane)");
  }

  if (light.shape == LightShape::Rect) {
    light.size = glm::vec2(f.scalarOrVec("size", glm::vec3(1.0f), 2));
    if (!(light.size.x > 0.0f && light.size.y > 0.0f)) {
      ctx.fail(f.at("size"), "an area light needs a positive size, got [" + Fields::fmtFloat(light.size.x) + ", " +
                                 Fields::fmtFloat(light.size.y) + "]");
    }
  } else if (light.shape != LightShape::Point) {
    const float r = f.number("radius", 0.5f);
    if (!(r > 0.0f)) {
      ctx.fail(f.at("radius"), "an area light needs a positive radius, got " + Fields::fmtFloat(r));
    }
    light.size = glm::vec2(r, r);
  }

  if (light.shape != LightShape::Point) {
    if (f.has("texture") && f.has("frames")) ctx.fail(f.context(), "give \"texture\" or \"frames\", not both");
    if (f.has("texture")) {
      light.emissionFrames.push_back(loadTexture(ctx, f.string("texture", ""), f.at("texture")));
    } else if (const Json* frames = f.get("frames")) {
      if (!frames->is_array() || frames->empty()) ctx.fail(f.at("frames"), "expected a list of texture paths");
      for (std::size_t i = 0; i < frames->size(); ++i) {
        const std::string context = f.at("frames") + "[" + std::to_string(i) + "]";
        if (!(*frames)[i].is_string()) ctx.fail(context, "expected a path");
        light.emissionFrames.push_back(loadTexture(ctx, (*frames)[i].get<std::string>(), context));
      }
      light.fps = f.number("fps", 0.0f);
      if (light.emissionFrames.size() > 1 && !(light.fps > 0.0f)) {
        ctx.fail(f.at("fps"), "an animated light needs \"fps\" > 0");
      }
    }
  }
  // An emission texture's negative texels (an EXR may hold them) gave visibility layers of -5.
  for (const int t : light.emissionFrames) {
    const Image& image = ctx.scene.textures[std::size_t(t)].image;
    const std::size_t negative =
        std::size_t(std::count_if(image.data.begin(), image.data.end(), [](float v) { return v < 0.0f; }));
    if (negative > 0)
      ctx.fail(f.at(f.has("texture") ? "texture" : "frames"),
               fmt::format("'{}' has {} negative values (a light cannot emit negative radiance)",
                           ctx.scene.textures[std::size_t(t)].source, negative));
  }
  light.spin = readSpin(ctx, f, glm::vec3(0.0f));  // pivot: the world origin
  f.finish();
  ctx.scene.lights.push_back(std::move(light));
}

void readCamera(Context& ctx, const Json& item) {
  Fields f(ctx, item, "camera");
  Camera& c = ctx.scene.camera;
  c.position = f.vec3("position", c.position);
  c.target = f.vec3("target", c.target);
  c.up = f.vec3("up", c.up);
  c.fovY = f.number("fov", c.fovY);
  c.zNear = f.number("near", c.zNear);
  f.finish();
  const glm::vec3 view = c.target - c.position;
  if (!(glm::length(view) > 0.0f)) ctx.fail("camera", "position and target coincide");
  if (!(glm::length(c.up) > 0.0f)) ctx.fail("camera.up", "must be a non-zero vector");
  if (!(glm::length(glm::cross(glm::normalize(view), glm::normalize(c.up))) > 1e-6f)) {
    ctx.fail("camera.up", "is parallel to the viewing direction");
  }
  if (!(c.fovY > 0.0f && c.fovY < 180.0f)) ctx.fail("camera.fov", "must be in (0, 180) degrees");
  // A pixel spans 2 d tan(fov / 2) / height at distance d, and float resolves d to d 2^-23:
  // below 4 float steps a pixel, neighbouring pixels see the same float point (fov 1e-30
  // rendered one point stretched over the image). Relative to float, not to the scene's size.
  const double pixel = 2.0 * std::tan(double(c.fovY) * 3.14159265358979323846 / 360.0) / double(ctx.scene.height);
  const double step = 4.0 * std::ldexp(1.0, -23);
  if (pixel < step)
    ctx.fail("camera.fov",
             fmt::format("{:.3g} degrees: a pixel of the {}-row image would span {:.3g} of the distance it "
                         "looks at, below the {:.3g} float resolves; at least {:.3g} degrees",
                         c.fovY, ctx.scene.height, pixel, step,
                         2.0 * std::atan(step * double(ctx.scene.height) / 2.0) * 360.0 / 3.14159265358979323846));
  if (!(c.zNear > 0.0f)) ctx.fail("camera.near", "must be positive");
}

// Why float cannot hold the area light `l`, or "" (a
// light of size 1e19 tripped an Embree assertion; one of 1e-30 was said to need "a positive
// size"). Both bounds are relative to float itself, not to a chosen scene size:
// - too large: every technique forms s - p between a light sample s and a surface point p and
//   its squared length; with |components| <= R (the light's reach from the origin; geometry
//   beyond float's range is dropped and counted by the mesh loaders) that is at most
//   3 (2R)^2 = 12 R^2, which must stay below FLT_MAX, so R < sqrt(FLT_MAX / 12) ~ 5.3e18 (and
//   the area, at most (2R)^2, stays finite);
// - too small: the samples lie within the light's half-extent e of its centre c, which is
//   stored as a float; with e below 4 float spacings (ulps) of c's largest coordinate fewer than
//   9 representable positions span the light per axis, so its samples round onto a few points,
//   and an area below FLT_MIN underflows to 0. Either way the light is a point light in
//   disguise. (The bound is on c's own float spacing, so it holds wherever the light is.)
std::string lightExtentProblem(const Light& l) {
  const double w = l.size.x, h = l.shape == LightShape::Rect ? l.size.y : l.size.x;
  const double reachOfSize = l.shape == LightShape::Rect ? 0.5 * std::hypot(w, h) : w;
  const double halfMin = l.shape == LightShape::Rect ? 0.5 * std::min(w, h) : w;
  const glm::dvec3 c = glm::abs(glm::dvec3(l.position));
  const double centre = std::max({c.x, c.y, c.z});
  const double reach = centre + reachOfSize;
  const double maxReach = std::sqrt(double(std::numeric_limits<float>::max()) / 12.0);
  const std::string size =
      l.shape == LightShape::Rect ? fmt::format("size [{:g}, {:g}]", w, h) : fmt::format("radius {:g}", w);
  if (reach > maxReach)
    return fmt::format(
        "{} is beyond what float can hold: the light reaches {:.3g} from the "
        "origin, and squared distances across it overflow float above "
        "sqrt(FLT_MAX / 12) = {:.3g}",
        size, reach, maxReach);
  const float centreF = float(centre);
  const double ulp = double(std::nextafter(centreF, std::numeric_limits<float>::infinity()) - centreF);
  const double area = double(l.area());
  if (halfMin < 4.0 * ulp || !(area >= double(std::numeric_limits<float>::min())))
    return fmt::format(
        "{} is below what float resolves at the light's position: its samples "
        "would collapse onto its centre (half-extent {:.3g}; 4 float spacings at "
        "|position| {:.3g} are {:.3g}; area {:.3g}); use a point light or a larger "
        "size",
        size, halfMin, centre, 4.0 * ulp, area);
  return {};
}

}  // namespace

// ---------------------------------------------------------------------------------------------

Scene interpretScene(const Json& doc, const std::string& where, const std::string& baseDir,
                     const LoadOptions& options) {
  Scene scene;
  Context ctx{where, baseDir, scene, options, {}, {}, {}, {}};
  Fields f(ctx, doc, "scene");
  scene.name = f.string("name", "scene");
  f.get("description");  // free text, documented

  Material fallback;
  fallback.name = "default";
  scene.materials.push_back(fallback);

  if (const Json* v = f.get("resolution")) {
    const glm::vec3 r = f.toVec(*v, "resolution", 2);
    if (r.x != std::floor(r.x) || r.y != std::floor(r.y) || r.x < 1 || r.y < 1 || r.x > kMaxResolution ||
        r.y > kMaxResolution) {
      ctx.fail("resolution",
               "expected two integers in [1, " + std::to_string(kMaxResolution) + "], got " + shownJson(*v));
    }
    scene.width = int(r.x);
    scene.height = int(r.y);
  }
  scene.background = f.scalarOrVec("background", scene.background, 3);

  if (const Json* materials = arrayField(f, "materials", ctx)) {
    for (std::size_t i = 0; i < materials->size(); ++i) readMaterial(ctx, (*materials)[i], int(i));
  }
  if (const Json* objects = arrayField(f, "objects", ctx)) {
    for (std::size_t i = 0; i < objects->size(); ++i) readObject(ctx, (*objects)[i], int(i));
  }
  if (const Json* lights = arrayField(f, "lights", ctx)) {
    for (std::size_t i = 0; i < lights->size(); ++i) readLight(ctx, (*lights)[i], int(i));
  }
  if (const Json* camera = f.get("camera")) {
    readCamera(ctx, *camera);
  } else {
    glm::vec3 lo, hi;
    scene.bounds(lo, hi);
    // Bounds near float's range (a huge but finite model) cannot be framed: say so rather than
    // report the computed camera's Inf as if the user had written it.
    if (!isFinite(0.5f * (hi - lo)) || !isFinite(hi - lo) || !isFinite(0.5f * (lo + hi))) {
      ctx.fail("camera",
               "the scene's bounds are too large to frame automatically; give a "
               "\"camera\"");
    }
    readCamera(ctx, framingCamera(lo, hi));
  }
  if (!scene.meshes.empty()) {
    // A near plane beyond every object (`near` 1e30) rendered an empty image without a word.
    glm::vec3 lo, hi;
    scene.bounds(lo, hi);
    double farthest = 0.0;
    for (int c = 0; c < 8; ++c) {
      const glm::dvec3 corner((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
      farthest = std::max(farthest, glm::length(corner - glm::dvec3(scene.camera.position)));
    }
    if (double(scene.camera.zNear) >= farthest)
      ctx.fail("camera.near",
               fmt::format("{} is beyond every object (the farthest point of the scene's bounds is {:.6g} "
                           "from the camera): nothing would be drawn",
                           scene.camera.zNear, farthest));
  }
  f.finish();

  // Lights that came from glTF files are checked here too: a zero-scale node or a NaN in a
  // file must not reach a renderer.
  std::map<std::string, std::size_t> lightNames;
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    const std::string context = describe("lights", int(i), l.name);
    const bool finite = isFinite(l.position) && isFinite(l.normal) && isFinite(l.tangent) &&
                        isFinite(glm::vec3(l.size, 0.0f)) && isFinite(l.color) && std::isfinite(l.intensity);
    if (!finite) ctx.fail(context, "has a NaN or infinite parameter");
    // glTF lights too (the scene file's own are refused as read): a light cannot emit negative
    // radiance.
    if (l.intensity < 0.0f || l.color.r < 0.0f || l.color.g < 0.0f || l.color.b < 0.0f)
      ctx.fail(context, "a negative intensity or colour (a light cannot emit negative radiance)");
    if (const auto [it, fresh] = lightNames.emplace(l.name, i); !fresh)
      ctx.fail(context, "has the name of " + describe("lights", int(it->second), l.name) +
                            ": light names must differ (they name each light's files and report rows)");
    if (l.isArea()) {
      if (const std::string why = lightExtentProblem(l); !why.empty()) ctx.fail(context, why);
    }
  }
  if (scene.meshes.empty()) ctx.warn(where + ": the scene has no geometry");
  if (scene.lights.empty()) ctx.warn(where + ": the scene has no lights");
  return scene;
}

}  // namespace penumbra::detail
