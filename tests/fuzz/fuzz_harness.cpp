// See fuzz_harness.h. Everything an input can reach goes through penumbra::loadScene, the entry
// point the CLI uses, so a bare mesh or glTF file is also framed by a camera and a floor from
// its bounds (bareGeometryDocument), which a NaN or huge coordinate must not break either.
#include "fuzz_harness.h"

#include <stdlib.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <typeinfo>

#include "core/error.h"
#include "core/image_io.h"
#include "core/memory.h"
#include "scene/scene.h"

namespace penumbra::fuzz {
namespace {

namespace fs = std::filesystem;

// A unit cube: 8 float3 positions then 36 uint16 indices (tests/data/scene/cube.bin).
const char kCubeBase64[] =
    "AAAAvwAAAL8AAAC/AAAAPwAAAL8AAAC/AAAAvwAAAD8AAAC/AAAAPwAAAD8AAAC/AAAAvwAAAL8AAAA/AAAAPwAAAL8A"
    "AAA/AAAAvwAAAD8AAAA/AAAAPwAAAD8AAAA/AQADAAcAAQAHAAUAAAAEAAYAAAAGAAIAAgAGAAcAAgAHAAMAAAABAAUA"
    "AAAFAAQABAAFAAcABAAHAAYAAAACAAMAAAADAAEA";

std::string decodeBase64(const std::string& s) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    return c == '+' ? 62 : c == '/' ? 63 : -1;
  };
  std::string out;
  unsigned bits = 0;
  int count = 0;
  for (char c : s) {
    const int v = value(c);
    if (v < 0) break;
    bits = bits << 6 | unsigned(v);
    count += 6;
    if (count >= 8) {
      count -= 8;
      out += char((bits >> count) & 0xff);
    }
  }
  return out;
}

void writeFile(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

std::string makeWorkspace() {
  std::string pattern = (fs::temp_directory_path() / "penumbra_fuzz_XXXXXX").string();
  if (!::mkdtemp(pattern.data())) {
    std::perror("penumbra fuzz: mkdtemp");
    std::abort();
  }
  const fs::path dir = pattern;
  const std::string cube = decodeBase64(kCubeBase64);
  writeFile(dir / "cube.bin", cube);
  writeFile(dir / "cube.gltf",
            "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
            "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
            "\"buffers\":[{\"byteLength\":168,\"uri\":\"cube.bin\"}],"
            "\"bufferViews\":[{\"buffer\":0,\"byteLength\":96},"
            "{\"buffer\":0,\"byteOffset\":96,\"byteLength\":72}],"
            "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":8,\"type\":\"VEC3\"},"
            "{\"bufferView\":1,\"componentType\":5123,\"count\":36,\"type\":\"SCALAR\"}]}");
  writeFile(dir / "mesh.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  Image tex(4, 4, 3, 0.5f);
  tex.at(1, 1, 0) = 2.0f;
  writePng((dir / "tex.png").string(), tex);
  writeExr((dir / "tex.exr").string(), {{"", &tex}});
  // The texture targets load their input as the light's and a material's texture.
  for (const char* ext : {"exr", "png"}) {
    writeFile(dir / (std::string("texture_") + ext + ".json"),
              std::string("{\"materials\":[{\"name\":\"m\",\"texture\":\"input.") + ext +
                  "\"}],\"objects\":[{\"shape\":\"plane\",\"material\":\"m\"}],"
                  "\"lights\":[{\"type\":\"rect\",\"position\":[0,2,0],\"texture\":\"input." +
                  ext + "\"}]}");
  }
  return dir.string();
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// What a renderer relies on once loadScene has returned. Returns the first violation.
std::string checkScene(const Scene& s) {
  if (s.materials.empty()) return "no materials (the default material is missing)";
  for (const Material& m : s.materials) {
    if (m.baseColorTexture < -1 || m.baseColorTexture >= int(s.textures.size()))
      return "material '" + m.name + "': texture index out of range";
    if (!(m.opacity >= 0.0f && m.opacity <= 1.0f)) return "material '" + m.name + "': opacity";
    if (!finite(m.baseColor)) return "material '" + m.name + "': non-finite colour";
  }
  for (const Texture& t : s.textures) {
    if (t.image.empty() ||
        t.image.data.size() != std::size_t(t.image.width) * std::size_t(t.image.height) * std::size_t(t.image.channels))
      return "texture " + t.source + ": empty or inconsistent size";
    for (float v : t.image.data)
      if (!std::isfinite(v)) return "texture " + t.source + ": non-finite texel";
  }
  for (const SceneMesh& sm : s.meshes) {
    const geo::TriangleMesh& m = sm.mesh;
    if (sm.material < 0 || std::size_t(sm.material) >= s.materials.size())
      return "mesh " + sm.name + ": material index out of range";
    if (!m.normals.empty() && m.normals.size() != m.positions.size())
      return "mesh " + sm.name + ": normals do not match positions";
    if (!m.uvs.empty() && m.uvs.size() != m.positions.size()) return "mesh " + sm.name + ": uvs do not match positions";
    for (const glm::uvec3& t : m.triangles) {
      for (int k = 0; k < 3; ++k) {
        if (t[k] >= m.positions.size()) return "mesh " + sm.name + ": index out of range";
        if (!finite(m.positions[t[k]])) return "mesh " + sm.name + ": non-finite kept vertex";
      }
    }
    if (sm.report.triangles != m.triangles.size() && sm.report.triangles != 0)
      return "mesh " + sm.name + ": report and mesh disagree on the triangle count";
  }
  for (const Light& l : s.lights) {
    if (!finite(l.position) || !finite(l.normal) || !finite(l.tangent) || !finite(l.color) ||
        !std::isfinite(l.intensity) || !std::isfinite(l.size.x) || !std::isfinite(l.size.y))
      return "light '" + l.name + "': non-finite parameter";
    if (l.isArea() && !(l.area() > 0.0f)) return "light '" + l.name + "': no area";
    for (int f : l.emissionFrames)
      if (f < 0 || f >= int(s.textures.size())) return "light '" + l.name + "': bad texture";
  }
  const Camera& c = s.camera;
  if (!finite(c.position) || !finite(c.target) || !finite(c.up) || !std::isfinite(c.fovY) || !std::isfinite(c.zNear))
    return "camera: non-finite parameter";
  if (s.width < 1 || s.height < 1 || s.width > 16384 || s.height > 16384) return "resolution";
  glm::vec3 lo, hi;
  s.bounds(lo, hi);
  if (!finite(lo) || !finite(hi)) return "bounds are not finite";
  return {};
}

}  // namespace

const std::vector<std::string>& formats() {
  static const std::vector<std::string> kFormats = {"gltf", "glb", "json", "obj", "ply", "off", "stl", "exr", "png"};
  return kFormats;
}

const std::string& workspace() {
  // Never destroyed: the exit handler that removes the folder runs after static destructors.
  static const std::string* dir = [] {
    setMemoryBudget(double(kMaxInputBytes));
    const auto* d = new std::string(makeWorkspace());
    std::atexit([] {
      std::error_code ec;
      fs::remove_all(workspace(), ec);
    });
    return d;
  }();
  return *dir;
}

Verdict loadInput(const std::string& format, const std::uint8_t* data, std::size_t size) {
  const fs::path dir = workspace();
  const std::string input = (dir / ("input." + format)).string();
  writeFile(input, std::string(reinterpret_cast<const char*>(data), size));
  const bool texture = format == "exr" || format == "png";
  const std::string scene = texture ? (dir / ("texture_" + format + ".json")).string() : input;
  Verdict v;
  try {
    const Scene s = loadScene(scene);
    v.loaded = true;
    v.problem = checkScene(s);
    if (!v.problem.empty()) v.problem = scene + " loaded, but " + v.problem;
  } catch (const Error& e) {
    v.message = e.what();
    // One line, naming a file of the workspace (the input, or a file the scene refers to).
    if (v.message.find('\n') != std::string::npos)
      v.problem = "multi-line error: " + v.message;
    else if (e.where().empty() || v.message.find(dir.string()) == std::string::npos)
      v.problem = "error does not name the file: " + v.message;
  } catch (const std::exception& e) {
    v.problem = std::string("exception other than penumbra::Error (") + typeid(e).name() + "): " + e.what();
  } catch (...) {
    v.problem = "unknown exception type";
  }
  return v;
}

}  // namespace penumbra::fuzz
