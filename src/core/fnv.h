// FNV-1a 64 (Fowler, Noll, Vo): the checksums and pattern hashes of penumbra's table files
// (luts/*.lut). Not a cryptographic hash: it finds corruption and mismatched inputs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include <fmt/format.h>

namespace penumbra {

struct Fnv1a {
  std::uint64_t h = 1469598103934665603ull;
  void bytes(const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  }
  template <class T>
  void value(const T& v) {
    bytes(&v, sizeof v);
  }
};

// 16 lower-case hex digits, as the table headers write hashes.
inline std::string hex64(std::uint64_t v) { return fmt::format("{:016x}", v); }

}  // namespace penumbra
