// Helpers shared by the scene tests.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <string>

#include "core/error.h"
#include "test_util.h"
#include "scene/scene.h"

namespace penumbra::test {

inline std::string sceneData(const std::string& name) {
  return std::string(PENUMBRA_SOURCE_DIR) + "/tests/data/scene/" + name;
}

inline std::string sourcePath(const std::string& relative) {
  return std::string(PENUMBRA_SOURCE_DIR) + "/" + relative;
}

// A fresh folder under the system temp dir, removed with the object.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("penumbra_scene_" + std::string(info ? info->name() : "x") + "_" +
             std::to_string(::getpid()));
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

inline bool hasWarning(const Scene& s, const std::string& fragment) {
  for (const std::string& w : s.warnings) {
    if (w.find(fragment) != std::string::npos) return true;
  }
  return false;
}

}  // namespace penumbra::test
