// Shared test helpers for every test executable.
#pragma once

#include <gtest/gtest.h>

#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <string>

#include "core/error.h"

namespace penumbra::test {

// Expects `f` to throw penumbra::Error with a one-line message that names `file` and contains
// `fragment` (CODE_STYLE.md "Errors": one line naming the file and the problem).
template <class F>
void expectError(F&& f, const std::string& file, const std::string& fragment = "") {
  try {
    f();
    ADD_FAILURE() << "no penumbra::Error for " << file << " (expected '" << fragment << "')";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(file), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "multi-line: " << what;
  }
}

// A gtest parameter name from a scene path: "scenes/hard/01-cube.json" -> "01_cube".
inline std::string sceneTestName(const std::string& path) {
  std::string n = path.substr(path.rfind('/') + 1);
  n = n.substr(0, n.find('.'));
  for (auto& ch : n)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return n;
}

// A fresh folder per test under the system temp folder, removed afterwards (also when the test
// made it read-only).
class TempDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("penumbra_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    std::filesystem::permissions(dir_, std::filesystem::perms::owner_all, std::filesystem::perm_options::add, ec);
    std::filesystem::remove_all(dir_, ec);
  }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }

  std::filesystem::path dir_;
};

}  // namespace penumbra::test
