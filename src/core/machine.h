// The machine a run is made on, for the records that carry timings (bench/results/<machine>/,
// a study's job rows): timings from different machines or renderers are never mixed.
#pragma once

#include <string>

namespace penumbra {

// The value of the first line of `path` that starts with `key` ("model name : AMD EPYC" ->
// "AMD EPYC"), quotes and blanks trimmed; "unknown" if none (/proc/cpuinfo, /etc/os-release).
std::string firstLine(const std::string& path, const std::string& key);

struct MachineFacts {
  std::string host, cpu, memory, os;
  unsigned cores = 0;
};
MachineFacts machineFacts();

// "cpu-2core-llvmpipe" for Mesa's CPU rasteriser, else the renderer's first words
// ("NVIDIA H200/PCIe/SSE2" -> "nvidia-h200"): the folder of a machine's results.
std::string machineName(const std::string& renderer);

}  // namespace penumbra
