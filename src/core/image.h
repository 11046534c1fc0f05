// Linear float images, row 0 at the top (as written to files). Interleaved channels.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace penumbra {

struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<float> data;  // width * height * channels, row-major, top row first

  Image() = default;
  Image(int w, int h, int c, float fill = 0.0f)
      : width(w), height(h), channels(c), data(std::size_t(w) * h * c, fill) {}

  std::size_t pixelCount() const { return std::size_t(width) * height; }
  float& at(int x, int y, int c) { return data[(std::size_t(y) * width + x) * channels + c]; }
  float at(int x, int y, int c) const { return data[(std::size_t(y) * width + x) * channels + c]; }
  bool empty() const { return data.empty(); }
};

}  // namespace penumbra
