#include "compare/insets.h"

#include <algorithm>
#include <cstdint>

namespace penumbra {

std::vector<Inset> chooseInsets(const FrameResult& ref, int count) {
  const int W = ref.color.width, H = ref.color.height;
  const int size = std::max(8, std::min(W, H) / 5);
  if (size > W || size > H) return {};
  // Penumbra pixels of any light, then a summed-area table for the window sums.
  std::vector<std::int64_t> sat(std::size_t(W + 1) * (H + 1), 0);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      int pen = 0;
      std::size_t i = std::size_t(y) * W + x;
      if (ref.gbuffer.valid.empty() || ref.gbuffer.valid[i])
        for (auto& l : ref.lights) {
          float v = l.visibility.data[i * 3];
          pen |= v > 0.02f && v < 0.98f;
        }
      sat[std::size_t(y + 1) * (W + 1) + x + 1] = pen + sat[std::size_t(y) * (W + 1) + x + 1] +
                                                  sat[std::size_t(y + 1) * (W + 1) + x] -
                                                  sat[std::size_t(y) * (W + 1) + x];
    }
  auto sum = [&](int x, int y) {
    auto at = [&](int xx, int yy) { return sat[std::size_t(yy) * (W + 1) + xx]; };
    return at(x + size, y + size) - at(x, y + size) - at(x + size, y) + at(x, y);
  };
  std::vector<Inset> out;
  const int step = std::max(1, size / 4);
  for (int n = 0; n < count; ++n) {
    std::int64_t best = 0;
    Inset pick;
    for (int y = 0; y + size <= H; y += step)
      for (int x = 0; x + size <= W; x += step) {
        bool overlaps = false;
        for (auto& o : out) overlaps |= x < o.x + o.w && o.x < x + size && y < o.y + o.h && o.y < y + size;
        std::int64_t s = overlaps ? -1 : sum(x, y);
        if (s > best) best = s, pick = {x, y, size, size};
      }
    if (best == 0) break;  // no (more) penumbra: no inset rather than an empty one
    out.push_back(pick);
  }
  return out;
}

Image crop(const Image& im, const Inset& r, int zoom) {
  Image out(r.w * zoom, r.h * zoom, im.channels);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < im.channels; ++c) out.at(x, y, c) = im.at(r.x + x / zoom, r.y + y / zoom, c);
  return out;
}

}  // namespace penumbra
