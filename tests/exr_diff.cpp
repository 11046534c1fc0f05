// exr_diff A.exr B.exr: compares the pixel data of two EXR files written by penumbra (the colour
// layer and every visibility layer present in A), bit for bit. Prints one line per layer that
// differs (pixels differing, max |difference|) and exits 0 when all are identical, 1 when any
// differs, 2 on a read error. Used by tests/determinism_test.sh, so that the test does not
// depend on the EXR writer being byte-deterministic.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "core/error.h"
#include "core/image_io.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: exr_diff A.exr B.exr\n");
    return 2;
  }
  int differing = 0;
  try {
    for (int l = 0; l < 9; ++l) {
      const std::string layer = l == 0 ? "" : l == 1 ? "visibility" : "visibility" + std::to_string(l - 1);
      penumbra::Image a, b;
      try {
        a = penumbra::readExrLayer(argv[1], layer);
      } catch (const penumbra::Error&) {
        if (l == 0) throw;
        continue;  // no such layer in A
      }
      b = penumbra::readExrLayer(argv[2], layer);
      if (a.width != b.width || a.height != b.height || a.channels != b.channels) {
        std::printf("layer '%s': sizes differ\n", layer.c_str());
        ++differing;
        continue;
      }
      std::size_t pixels = 0;
      double maxDiff = 0.0;
      for (std::size_t p = 0; p < a.pixelCount(); ++p) {
        bool same = true;
        for (int c = 0; c < a.channels; ++c) {
          const float x = a.data[p * a.channels + c], y = b.data[p * a.channels + c];
          if (std::memcmp(&x, &y, sizeof x) != 0) {
            same = false;
            maxDiff = std::fmax(maxDiff, std::fabs(double(x) - double(y)));
          }
        }
        pixels += !same;
      }
      if (pixels) {
        std::printf("layer '%s': %zu of %zu pixels differ, max |difference| %.3g\n", layer.c_str(), pixels,
                    a.pixelCount(), maxDiff);
        ++differing;
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "exr_diff: %s\n", e.what());
    return 2;
  }
  return differing ? 1 : 0;
}
