// Insets: zoomed regions of the first preset's images, where the techniques differ most.
#pragma once

#include <vector>

#include "core/image.h"
#include "pipeline/renderer.h"

namespace penumbra {

// A zoomed region of the first preset's images, in its pixels (x, y from the top left).
struct Inset {
  int x = 0, y = 0, w = 0, h = 0;
};

// Two square regions where the reference has the most penumbra pixels (visibility strictly
// between 0 and 1), not overlapping: where techniques differ most.
std::vector<Inset> chooseInsets(const FrameResult& reference, int count = 2);

// The region `r` of `im` scaled up by `zoom` (nearest).
Image crop(const Image& im, const Inset& r, int zoom);

}  // namespace penumbra
