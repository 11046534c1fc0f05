// The light-sample set a pixel uses, the same decision in C++ (sampling/light_samples.cpp) and
// GLSL (the pipeline's common_light.glsl). Valid in both (shared/shared.h); C++ includes it
// through sampling/sample_sets.hpp.
#ifndef PENUMBRA_SAMPLE_SETS_H
#define PENUMBRA_SAMPLE_SETS_H

#include "shared/numerics.h"

// The light-sample set a pixel uses. Correlated: set 0 everywhere. Decorrelated: a hash of the
// pixel and seed picks one of `sets` rotated sets. Interleaved: the pixel's position in a K x K
// tile picks the set (sets == K*K).
PENUMBRA_FN uint penumbraSetForPixel(uint x, uint y, uint pattern, uint sets, uint k, uint seed) {
  if (pattern == uint(PENUMBRA_PATTERN_DECORRELATED))
    return penumbraHash(x ^ penumbraHash(y ^ penumbraHash(seed))) % sets;
  if (pattern == uint(PENUMBRA_PATTERN_INTERLEAVED)) return (y % k) * k + (x % k);
  return 0u;
}

#endif
