#include "core/machine.h"

#include <unistd.h>

#include <cctype>
#include <fstream>
#include <thread>

#include <fmt/format.h>

namespace penumbra {

std::string firstLine(const std::string& path, const std::string& key) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key, 0) == 0) {
      auto p = line.find_first_of(":=", key.size());
      std::string v = p == std::string::npos ? line : line.substr(p + 1);
      v.erase(0, v.find_first_not_of(" \t\""));
      while (!v.empty() && (v.back() == '"' || v.back() == ' ')) v.pop_back();
      return v;
    }
  return "unknown";
}

MachineFacts machineFacts() {
  MachineFacts m;
  char host[256] = {};
  m.host = ::gethostname(host, sizeof host - 1) == 0 ? host : "unknown";
  m.cpu = firstLine("/proc/cpuinfo", "model name");
  m.memory = firstLine("/proc/meminfo", "MemTotal");
  m.os = firstLine("/etc/os-release", "PRETTY_NAME");
  m.cores = std::thread::hardware_concurrency();
  return m;
}

std::string machineName(const std::string& renderer) {
  if (renderer.find("llvmpipe") != std::string::npos)
    return fmt::format("cpu-{}core-llvmpipe", std::thread::hardware_concurrency());
  std::string out;
  int words = 0;
  for (char c : renderer) {
    if (std::isalnum(static_cast<unsigned char>(c))) {
      out += char(std::tolower(static_cast<unsigned char>(c)));
    } else if (!out.empty() && out.back() != '-') {
      if (++words == 2) break;
      out += '-';
    }
  }
  while (!out.empty() && out.back() == '-') out.pop_back();
  return out.empty() ? "unknown-gpu" : out;
}

}  // namespace penumbra
