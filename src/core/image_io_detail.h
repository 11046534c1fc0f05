// Helpers shared by the image readers and writers (exr_io.cpp, png_io.cpp, image_io.cpp); not
// part of image_io.h's interface.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

namespace penumbra::image_io_detail {

// The largest width or height a reader accepts (checked before allocating).
constexpr std::int64_t kMaxDimension = 16384;

// Library messages can span lines; main() promises one line per error.
inline std::string oneLine(std::string s) {
  std::replace_if(
      s.begin(), s.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

inline std::string errnoText(int err) { return err != 0 ? std::strerror(err) : "unknown error"; }

inline std::string sizeText(std::int64_t w, std::int64_t h) { return std::to_string(w) + "x" + std::to_string(h); }

using FilePtr = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

}  // namespace penumbra::image_io_detail
