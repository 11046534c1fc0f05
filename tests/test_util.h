// Shared test helpers for every test executable.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "core/error.h"

namespace penumbra::test {

// Expects `f` to throw penumbra::Error with a one-line message that names `file` and contains
// `fragment` (README "Errors": one line naming the file and the problem).
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

}  // namespace penumbra::test
