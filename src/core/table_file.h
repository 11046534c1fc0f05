// penumbra's table files (luts/*.lut: the LTC GGX table, dcs's edge LUTs): a text header, then a
// little-endian binary payload. The header is the magic line ("<kind> <format>"), one "key value"
// line per key (every key of the kind once, no other, each line at most 200 bytes), then
// "checksum <16 hex digits>" and "end". The checksum is FNV-1a 64 (core/fnv.h) of the header's
// lines above it, each with its newline, then the payload: an edited header value is a corrupt
// file, as an edited payload is. One reader and writer for every kind.
#pragma once

#include <cstddef>
#include <cstdint>
#include <istream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/fnv.h"

namespace penumbra {

struct TableHeader {
  std::string path;
  std::map<std::string, std::string> values;  // key -> the rest of its line
  std::string covered;                        // the lines the checksum covers, magic first
  std::string checksum;                       // as written: 16 hex digits

  // The value of `key` read as a T; Error(path, "bad header line ...") where it is not one.
  template <class T>
  T get(const std::string& key) const {
    std::istringstream in(values.at(key));
    T v{};
    if (!(in >> v) || !(in >> std::ws).eof())
      throw Error(path, "bad header line '" + abbreviate(key + " " + values.at(key)) + "'");
    return v;
  }
  // Error(path, "checksum mismatch (corrupt or edited file)") unless `payload` (its bytes, in
  // file order, after the covered lines) gives the header's checksum.
  void checkChecksum(const std::vector<std::pair<const void*, std::size_t>>& payload) const;
};

// The checksum of `covered` then `payload`.
std::uint64_t tableChecksum(const std::string& covered,
                            const std::vector<std::pair<const void*, std::size_t>>& payload);

// Reads the header from `in`, at the file's start, leaving `in` at the payload. `magic` is the
// whole first line; `keys` the keys the header holds, all and only these.
TableHeader readTableHeader(std::istream& in, const std::string& path, const std::string& magic,
                            const std::vector<std::string>& keys);

// The lines a header's checksum covers: the magic line and "key value" for each pair, in order.
std::string tableHeaderLines(const std::string& magic, const std::vector<std::pair<std::string, std::string>>& values);

// The whole header: `covered`, then the checksum of it and `payload`, then "end".
std::string tableHeader(const std::string& covered, const std::vector<std::pair<const void*, std::size_t>>& payload);

}  // namespace penumbra
