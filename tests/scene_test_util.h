// Helpers shared by the scene tests.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <nlohmann/json.hpp>
#include <glm/glm.hpp>
#include <string>

#include "core/error.h"
#include "test_util.h"
#include "scene/scene.h"

namespace penumbra::test {

inline std::string sceneData(const std::string& name) {
  return std::string(PENUMBRA_SOURCE_DIR) + "/tests/data/scene/" + name;
}

inline std::string sourcePath(const std::string& relative) { return std::string(PENUMBRA_SOURCE_DIR) + "/" + relative; }

// A fresh folder under the system temp dir, removed with the object.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("penumbra_scene_" + std::string(info ? info->name() : "x") + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  std::string file(const std::string& name, const std::string& contents) const {
    const auto p = path_ / name;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << contents;
    return p.string();
  }
  std::string path() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

// Six times the signed volume: positive for a closed mesh wound counter-clockwise outward.
inline double signedVolume(const geo::TriangleMesh& m) {
  double v = 0.0;
  for (const glm::uvec3& t : m.triangles) {
    const glm::dvec3 a = m.positions[t.x], b = m.positions[t.y], c = m.positions[t.z];
    v += glm::dot(a, glm::cross(b, c));
  }
  return v / 6.0;
}

using test::expectError;  // tests/test_util.h

// tests/data/scene/cube.gltf: one node, one mesh, 8 float positions and 36 uint16 indices in
// one data: URI buffer (positions at 0, indices at 96).
inline nlohmann::json cubeDocument() {
  std::ifstream in(sceneData("cube.gltf"));
  std::stringstream text;
  text << in.rdbuf();
  return nlohmann::json::parse(text.str());
}

inline std::string base64(const std::string& bytes) {
  static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 3; ++k) v = v << 8 | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k) out += k <= n ? kAlphabet[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

// A scene file whose material and rect light both use `texture`.
inline std::string sceneWithTexture(const std::string& texture) {
  return R"({"materials": [{"name": "m", "texture": ")" + texture +
         R"("}], "objects": [{"shape": "plane", "material": "m"}],
             "lights": [{"type": "rect", "position": [0, 2, 0], "texture": ")" +
         texture + R"("}]})";
}

inline bool hasWarning(const Scene& s, const std::string& fragment) {
  for (const std::string& w : s.warnings) {
    if (w.find(fragment) != std::string::npos) return true;
  }
  return false;
}

}  // namespace penumbra::test
