// The light samples of a pixel that its few rays go to (smrt, contact shadows): ray i of R goes
// to sample first + (i + 0.5) N / R (mod N), a stratified subset of the pixel's N samples (all of
// them when R >= N), `first` rotating it per pixel. The estimate of (1/N) sum L_k V_k is the
// subset's mean of L_k V_k.
// Sterna, Listing 2 (Jimenez 2014): per-pixel noise in [0, 1).
float interleavedGradientNoise(vec2 pixel) {
  return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}

int raysTraced(int rays, int samples) { return min(rays, samples); }
uint raySample(int i, int traced, int samples, int first) {
  return uint((first + int((float(i) + 0.5) * float(samples) / float(traced))) % samples);
}
// The share of the traced rays' luminance that arrives (`lit` of `total`); 1 where no ray counted.
vec3 arrivingShare(vec3 lit, vec3 total) {
  return mix(vec3(1.0), lit / max(total, vec3(1e-30)), greaterThan(total, vec3(0.0)));
}
