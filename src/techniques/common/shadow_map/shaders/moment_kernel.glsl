// The summed-area-table techniques' kernels (vssm, msm), after pcss_common.glsl and
// vssm_common.glsl.

// The receiver's biased view depth, and its normalised depth, where its plane crosses the ray
// through texel coordinate c
// (receiver-plane depth, as every shadow-map technique here: a tilted receiver compares each
// sub-kernel with its own plane's depth there, not with the depth at its centre).
float receiverDepthAt(Receiver r, vec2 c) {
  vec2 uv = c / float(mapSize);
  return planeDepth(r.o, r.n, lightPosition, vec2(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0), r.d) - r.bias;
}
float receiverAt(Receiver r, vec2 c) { return normalisedDepth(receiverDepthAt(r, c)); }

// The texel box [lo, hi] of a kernel around uv of half-size radius (uv units).
void kernelBox(Receiver r, float radius, out ivec2 lo, out ivec2 hi) {
  vec2 c = r.uv * float(mapSize);
  float extent = max(radius * float(mapSize), 0.5);
  lo = clamp(ivec2(floor(c - extent)), ivec2(0), ivec2(mapSize - 1));
  hi = clamp(ivec2(floor(c + extent)), ivec2(0), ivec2(mapSize - 1));
}

// Cell (x, y) of `cells` x `cells` of the box [lo, hi]; false if empty.
bool cellBox(ivec2 lo, ivec2 hi, int cells, ivec2 cell, out ivec2 a, out ivec2 b) {
  ivec2 span = hi - lo + 1;
  a = lo + (span * cell) / cells;
  b = lo + (span * (cell + 1)) / cells - 1;
  return all(greaterThanEqual(b, a));
}
