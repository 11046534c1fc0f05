#include "core/memory.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <string>

#include <fmt/format.h>

#include "core/error.h"

namespace penumbra {
namespace {

// A "Vm...:" line of /proc/self/status, in bytes (0 when absent).
double procStatusBytes(const std::string& key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key + ":", 0) == 0) return std::stod(line.substr(key.size() + 1)) * 1024.0;
  return 0.0;
}

double gBudget = 0.0;  // setMemoryBudget

struct Budget {
  double bytes;
  std::string limit;  // which one decides, for messages
};

Budget budget() {
  Budget b{double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE)), "physical memory"};
  const std::pair<int, const char*> limits[] = {{RLIMIT_AS, "VmSize"}, {RLIMIT_DATA, "VmData"}};
  for (const auto& [resource, used] : limits) {
    rlimit r{};
    if (getrlimit(resource, &r) != 0 || r.rlim_cur == RLIM_INFINITY) continue;
    const double left = std::max(0.0, double(r.rlim_cur) - procStatusBytes(used));
    if (left < b.bytes)
      b = {left, fmt::format("{} limit of {:.0f} MiB less {:.0f} MiB in use",
                             resource == RLIMIT_AS ? "ulimit -v" : "ulimit -d", double(r.rlim_cur) / 1048576.0,
                             procStatusBytes(used) / 1048576.0)};
  }
  if (gBudget > 0.0) {
    const double held = procStatusBytes("VmRSS");
    const double left = std::max(0.0, gBudget - held);
    if (left < b.bytes)
      b = {left, fmt::format("the run's memory budget of {:.0f} MiB less {:.0f} MiB held", gBudget / 1048576.0,
                             held / 1048576.0)};
  }
  return b;
}

}  // namespace

double memoryBudgetBytes() { return budget().bytes; }

void setMemoryBudget(double bytes) { gBudget = bytes > 0.0 ? bytes : 0.0; }

void checkMemory(const std::string& where, const std::string& what, double bytes) {
  const Budget b = budget();
  if (bytes > b.bytes)
    throw MemoryError(
        where, fmt::format("{} needs about {:.0f} MiB, more than the {:.0f} MiB this process may allocate ({})", what,
                           bytes / 1048576.0, b.bytes / 1048576.0, b.limit));
}

}  // namespace penumbra
