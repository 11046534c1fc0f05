// penumbra's table files' header (core/table_file.h).
#include "core/table_file.h"

#include <algorithm>
#include <set>

namespace penumbra {

std::uint64_t tableChecksum(const std::string& covered,
                            const std::vector<std::pair<const void*, std::size_t>>& payload) {
  Fnv1a f;
  f.bytes(covered.data(), covered.size());
  for (const auto& [data, size] : payload) f.bytes(data, size);
  return f.h;
}

void TableHeader::checkChecksum(const std::vector<std::pair<const void*, std::size_t>>& payload) const {
  if (hex64(tableChecksum(covered, payload)) != checksum)
    throw Error(path, "checksum mismatch (corrupt or edited file)");
}

TableHeader readTableHeader(std::istream& in, const std::string& path, const std::string& magic,
                            const std::vector<std::string>& keys) {
  TableHeader h;
  h.path = path;
  std::string line;
  const std::string kind = magic.substr(0, magic.find(' '));
  if (!std::getline(in, line) || line.rfind(kind + " ", 0) != 0)
    throw Error(path, "not a " + kind + " file (expected '" + magic + "')");
  if (line != magic)
    throw Error(
        path, "format '" + abbreviate(line) + "', this build reads '" + magic + "': regenerate it with `penumbra lut`");
  h.covered = line + "\n";
  bool ended = false;
  std::set<std::string> seen;
  while (!ended && std::getline(in, line)) {
    if (line.size() > 200) throw Error(path, "header line too long");
    const std::size_t space = line.find(' ');
    const std::string key = line.substr(0, space);
    const std::string value = space == std::string::npos ? "" : line.substr(space + 1);
    if (key == "end") {
      ended = true;
      continue;
    }
    if (!seen.insert(key).second) throw Error(path, "header key '" + abbreviate(key) + "' given twice");
    if (key == "checksum") {
      h.checksum = value;
      if (value.size() != 16 || value.find_first_not_of("0123456789abcdef") != std::string::npos)
        throw Error(path, "bad header line '" + abbreviate(line) + "'");
      continue;
    }
    if (std::find(keys.begin(), keys.end(), key) == keys.end())
      throw Error(path, "unknown header line '" + abbreviate(line) + "'");
    if (!h.checksum.empty()) throw Error(path, "header line '" + abbreviate(line) + "' after the checksum");
    h.values[key] = value;
    h.covered += line + "\n";
  }
  if (!ended || h.checksum.empty() || h.values.size() != keys.size()) throw Error(path, "incomplete header");
  return h;
}

std::string tableHeaderLines(const std::string& magic, const std::vector<std::pair<std::string, std::string>>& values) {
  std::string s = magic + "\n";
  for (const auto& [key, value] : values) s += key + " " + value + "\n";
  return s;
}

std::string tableHeader(const std::string& covered, const std::vector<std::pair<const void*, std::size_t>>& payload) {
  return covered + "checksum " + hex64(tableChecksum(covered, payload)) + "\nend\n";
}

}  // namespace penumbra
