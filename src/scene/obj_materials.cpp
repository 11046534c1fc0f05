// OBJ materials: `mtllib` files are read for what a soft-shadow renderer
// uses — Kd (base colour), map_Kd (base-colour texture) and d / Tr (opacity, d = 1 - Tr; the
// MTL format of Wavefront's "Advanced Visualizer" manual, where Tr is the transparency some
// exporters write instead of d). Faces after `usemtl NAME` get that material: the OBJ is split
// into one mesh per material (geo::loadObjFile). Nothing is ignored silently: every other
// MTL statement is named in a warning ("not used"), an unknown usemtl name, a missing or refused
// library and a texture that cannot be read are warned about, and those faces keep the
// object's or the default material.
//
// Paths follow the glTF rule (docs/scene-format.md): a library is relative to the OBJ's folder,
// a texture to its library's folder, and both must stay inside the OBJ's folder (no "..",
// absolute path, scheme or shell metacharacter, no symlink leading out). A path that breaks the
// rule is refused with a warning rather than an error, as real MTL files often carry an
// exporter's absolute path ("C:\textures\wood.png"): the mesh still loads, nothing outside the
// folder is read.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/error.h"
#include "core/memory.h"
#include "core/key_values.h"
#include "scene/loaders.h"

namespace penumbra::detail {
namespace {

namespace fs = std::filesystem;

constexpr std::uintmax_t kMaxMtlBytes = 64u << 20;  // as scene files

std::string trim(const std::string& s) {
  const std::size_t b = s.find_first_not_of(" \t\r\f\v");
  if (b == std::string::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r\f\v") - b + 1);
}

std::vector<std::string> tokens(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> out;
  for (std::string t; in >> t;) out.push_back(t);
  return out;
}

// A finite float (core/key_values.h's parser).
bool parseFloat(const std::string& token, float& value) {
  double x = 0.0;
  if (!parseNumber(token, x)) return false;
  value = float(x);
  return std::isfinite(value);
}

// "a, b, c" with at most five names, then "and N more".
std::string nameList(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size() && i < 5; ++i) out += (i ? ", " : "") + names[i];
  if (names.size() > 5) out += " and " + std::to_string(names.size() - 5) + " more";
  return out;
}

// Why `reference` (relative to `folder`) may not be read, or "" with `resolved` set.
std::string referenceProblem(const std::string& reference, const fs::path& folder, const std::string& root,
                             std::string& resolved) {
  if (std::string why = relativePathProblem(reference); !why.empty()) return why;
  resolved = (folder / reference).lexically_normal().string();
  if (std::string why = fileProblem(resolved); !why.empty()) return why + " (" + resolved + ")";
  if (!isInsideFolder(resolved, root)) return "resolves outside " + root;
  return {};
}

struct MtlReader {
  Model& model;
  std::string objFolder;  // the root every path must stay inside
  const LoadOptions& options;
  std::map<std::string, int> materialByName;
  std::map<std::string, int> textureByPath;

  int texture(const std::string& mtl, const std::string& context, const std::string& reference) {
    std::string resolved;
    const std::string why = referenceProblem(reference, fs::path(mtl).parent_path(), objFolder, resolved);
    if (!why.empty()) {
      model.warnings.push_back(mtl + ": " + context + ": map_Kd '" + reference + "' " + why +
                               "; the material has no texture");
      return -1;
    }
    if (const auto it = textureByPath.find(resolved); it != textureByPath.end()) return it->second;
    Texture t;
    try {
      t = readTextureFile(resolved, model.warnings, options);
    } catch (const MemoryError&) {
      throw;  // a texture too large for memory stops the run; an unreadable one is dropped
    } catch (const Error& e) {
      model.warnings.push_back(mtl + ": " + context + ": map_Kd '" + reference + "' cannot be read (" + e.what() +
                               "); the material has no texture");
      return -1;
    }
    const int index = int(model.textures.size());
    model.textures.push_back(std::move(t));
    textureByPath[resolved] = index;
    return index;
  }

  void read(const std::string& mtl) {
    std::error_code ec;
    const auto size = fs::file_size(mtl, ec);
    if (ec || size > kMaxMtlBytes) {
      model.warnings.push_back(mtl + ": " + (ec ? "cannot read: " + ec.message() : std::string("larger than 64 MiB")) +
                               "; its materials are not read");
      return;
    }
    std::ifstream in(mtl, std::ios::binary);
    std::map<std::string, std::vector<std::string>> unused;  // key -> materials using it
    std::string line;
    int current = -1;  // index into model.materials; -1 before newmtl or for a repeated name
    bool hasD = false, hasTr = false;
    float tr = 0.0f;
    // Ks and Ns onto the glTF metallic-roughness BRDF: Ks > 0 turns the
    // specular lobe on, as a dielectric's (F0 0.04, metallic 0: MTL's Ks scales a Phong lobe, it
    // is not a reflectance at normal incidence, so its strength and colour are not used, said
    // once per file); Ns, the Blinn-Phong exponent, gives GGX alpha = sqrt(2 / (Ns + 2)) (Walter
    // et al. 2007, eq. 33's Beckmann-Phong correspondence), roughness = sqrt(alpha).
    glm::vec3 ks(0.0f);
    float ns = -1.0f;                   // -1: not given (roughness 1)
    std::vector<std::string> specular;  // materials whose Ks was mapped
    std::string currentName;
    const auto finishMaterial = [&] {
      if (current < 0) return;
      Material& m = model.materials[std::size_t(current)];
      if (std::max({ks.x, ks.y, ks.z}) > 0.0f) {
        m.brdf = BrdfModel::MetallicRoughness;
        m.metallic = 0.0f;
        m.roughness = ns >= 0.0f ? std::sqrt(std::sqrt(2.0f / (ns + 2.0f))) : 1.0f;
        specular.push_back(currentName);
      }
      if (!hasTr) return;
      if (!hasD) {
        m.opacity = 1.0f - tr;
      } else if (std::abs(m.opacity - (1.0f - tr)) > 1e-6f) {
        model.warnings.push_back(mtl + ": material '" + currentName + "': d " + std::to_string(m.opacity) + " and Tr " +
                                 std::to_string(tr) + " disagree; d is used");
      }
      m.alphaMode = m.opacity < 1.0f ? AlphaMode::Blend : AlphaMode::Opaque;
    };
    while (std::getline(in, line)) {
      line = line.substr(0, line.find('#'));
      std::istringstream words(line);
      std::string key;
      if (!(words >> key)) continue;
      std::string rest;
      std::getline(words, rest);
      rest = trim(rest);
      if (key == "newmtl") {
        finishMaterial();
        hasD = hasTr = false;
        ks = glm::vec3(0.0f), ns = -1.0f;
        currentName = rest;
        if (materialByName.count(rest)) {
          model.warnings.push_back(mtl + ": material '" + rest + "' is defined again; the first definition is used");
          current = -1;
          continue;
        }
        Material m;
        m.name = rest;
        current = int(model.materials.size());
        materialByName[rest] = current;
        model.materials.push_back(std::move(m));
        continue;
      }
      const std::string context = "material '" + currentName + "'";
      if (current < 0) {
        if (currentName.empty()) model.warnings.push_back(mtl + ": '" + key + "' before any newmtl ignored");
        continue;
      }
      Material& m = model.materials[std::size_t(current)];
      const std::vector<std::string> t = tokens(rest);
      if (key == "Kd") {
        float c[3] = {0.0f, 0.0f, 0.0f};
        bool ok = t.size() == 1 || t.size() == 3;
        for (std::size_t i = 0; ok && i < t.size(); ++i) ok = parseFloat(t[i], c[i]);
        if (t.size() == 1) c[1] = c[2] = c[0];  // "Kd r": g and b default to r
        if (!ok || c[0] < 0.0f || c[1] < 0.0f || c[2] < 0.0f) {
          model.warnings.push_back(mtl + ": " + context + ": Kd '" + rest +
                                   "' is not 1 or 3 finite numbers >= 0 (spectral and xyz are "
                                   "not supported); the base colour stays 0.8");
        } else {
          m.baseColor = glm::vec3(c[0], c[1], c[2]);
        }
      } else if (key == "Ks" || key == "Ns") {
        float c[3] = {0.0f, 0.0f, 0.0f};
        const std::size_t want = key == "Ns" ? 1 : 3;
        bool ok = t.size() == 1 || t.size() == want;
        for (std::size_t i = 0; ok && i < t.size(); ++i) ok = parseFloat(t[i], c[i]) && c[i] >= 0.0f;
        if (!ok) {
          model.warnings.push_back(mtl + ": " + context + ": " + key + " '" + rest + "' is not " +
                                   (want == 1 ? "a finite number" : "1 or 3 finite numbers") + " >= 0; ignored");
        } else if (key == "Ns") {
          ns = c[0];
        } else {
          ks = t.size() == 1 ? glm::vec3(c[0]) : glm::vec3(c[0], c[1], c[2]);
        }
      } else if (key == "d" || key == "Tr") {
        // "d -halo 0.5": the halo form (opacity by view angle) is read as plain d, warned.
        float value = 0.0f;
        const bool halo = key == "d" && t.size() == 2 && t[0] == "-halo";
        if (t.empty() || t.size() > 2 || (t.size() == 2 && !halo) || !parseFloat(t.back(), value) || value < 0.0f ||
            value > 1.0f) {
          model.warnings.push_back(mtl + ": " + context + ": " + key + " '" + rest +
                                   "' is not a number in [0, 1]; ignored");
          continue;
        }
        if (halo) model.warnings.push_back(mtl + ": " + context + ": d -halo is read as d " + t.back());
        if (key == "d") {
          m.opacity = value;
          m.alphaMode = value < 1.0f ? AlphaMode::Blend : AlphaMode::Opaque;
          hasD = true;
        } else {
          tr = value;
          hasTr = true;
        }
      } else if (key == "map_Kd") {
        // Options (-s, -o, -clamp, -mm, ...) come before the file name; they are not applied.
        std::string file = rest;
        if (!t.empty() && t[0].size() > 1 && t[0][0] == '-') {
          file = t.back();
          model.warnings.push_back(mtl + ": " + context + ": map_Kd options ignored ('" + rest +
                                   "'); the texture is '" + file + "'");
        }
        if (file.empty())
          model.warnings.push_back(mtl + ": " + context + ": map_Kd without a file name ignored");
        else
          m.baseColorTexture = texture(mtl, context, file);
      } else {
        unused[key].push_back(currentName);
      }
    }
    finishMaterial();
    if (!specular.empty())
      model.warnings.push_back(mtl +
                               ": Ks is read as a dielectric specular lobe (F0 0.04, roughness from Ns); "
                               "its strength and colour are not used, in " +
                               std::to_string(specular.size()) + " material" + (specular.size() == 1 ? "" : "s") +
                               " (" + nameList(specular) + ")");
    for (const auto& [key, names] : unused)
      model.warnings.push_back(mtl + ": '" + key +
                               "' not used (penumbra reads Kd, Ks, Ns, map_Kd, d and "
                               "Tr), in " +
                               std::to_string(names.size()) + " material" + (names.size() == 1 ? "" : "s") + " (" +
                               nameList(names) + ")");
  }
};

// The files one `mtllib` statement names. The statement lists file names separated by blanks,
// but exporters also write one name with spaces in it: the whole rest of the line is taken
// when that file exists.
std::vector<std::string> libraryNames(const std::string& statement, const fs::path& folder) {
  std::error_code ec;
  if (statement.find_first_of(" \t") == std::string::npos || fs::is_regular_file(folder / statement, ec))
    return {statement};
  return tokens(statement);
}

}  // namespace

Model loadObjModel(const std::string& path, const LoadOptions& options) {
  geo::ObjFile obj = geo::loadObjFile(path);
  Model model;
  const fs::path folder = fs::path(path).parent_path();
  MtlReader reader{model, folder.empty() ? std::string(".") : folder.string(), options, {}, {}};
  std::vector<std::string> libraries;
  for (const std::string& statement : obj.libraries) {
    for (const std::string& lib : libraryNames(statement, folder)) {
      std::string resolved;
      if (const std::string why = referenceProblem(lib, folder, reader.objFolder, resolved); !why.empty()) {
        model.warnings.push_back(path + ": mtllib '" + lib + "': " + why + "; its materials are not read");
        continue;
      }
      if (std::find(libraries.begin(), libraries.end(), resolved) != libraries.end()) continue;
      libraries.push_back(resolved);
      reader.read(resolved);
    }
  }
  for (geo::ObjPart& part : obj.parts) {
    SceneMesh sm;
    sm.name = part.material.empty() ? path : path + "#" + part.material;
    sm.mesh = std::move(part.mesh);
    sm.report = part.report;
    sm.material = -1;  // the object's material or the default
    if (!part.material.empty()) {
      if (const auto it = reader.materialByName.find(part.material); it != reader.materialByName.end()) {
        sm.material = it->second;
      } else {
        model.warnings.push_back(path + ": usemtl '" + part.material + "': " +
                                 (libraries.empty() ? std::string("no material library was read")
                                                    : "no such material in " + nameList(libraries)) +
                                 "; its " + std::to_string(sm.report.triangles) +
                                 " triangles use the object's or the default material");
      }
    }
    if (sm.mesh.triangles.empty()) {
      model.warnings.push_back(sm.name + ": no triangles left (" + sm.report.summary() + ")");
      continue;
    }
    // Vertices copied for the silhouette mesh change nothing loaded: counted, not warned.
    if (sm.report.worthWarning()) model.warnings.push_back(sm.name + ": " + sm.report.summary());
    model.meshes.push_back(std::move(sm));
  }
  return model;
}

}  // namespace penumbra::detail
