// SplitMix64 (Steele, Lea and Flood 2014): tiny, full-period, identical on every platform, so
// every sample set and estimate seeded from parameters is the same bytes everywhere. No std::
// distributions (their output differs between standard-library versions).
#pragma once

#include <cstdint>

namespace penumbra {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next() >> 11) * 0x1.0p-53; }  // [0,1), 53 bits
  std::uint32_t below(std::uint32_t n) { return std::uint32_t(uniform() * n); }

 private:
  std::uint64_t state_;
};

}  // namespace penumbra
