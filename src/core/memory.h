// Memory before allocating: a scene that needs more memory than this
// process may allocate is refused with one line before it is built, not killed half-way by
// std::bad_alloc or the OOM killer.
#pragma once

#include <string>

#include "core/error.h"

namespace penumbra {

// Bytes this process may still allocate: the smallest of physical memory, the address-space
// and data limits where set (`ulimit -v`, `ulimit -d`, less what the process has mapped) and the
// run's own budget where set (setMemoryBudget, less the memory the process holds).
double memoryBudgetBytes();

// The run's own memory budget in bytes (0: none, the default): what a user caps a run at so that
// an untrusted scene is refused before it allocates more (the fuzz targets run under 1 GiB).
void setMemoryBudget(double bytes);

// What checkMemory throws: a refusal no loader turns into a warning (a texture that cannot be read
// may be dropped with one; one that does not fit must stop the run).
class MemoryError : public Error {
 public:
  using Error::Error;
};

// Throws MemoryError(where, "<what> needs about <N> MiB, more than the <M> MiB this process may
// allocate (<which limit>)") when `bytes` exceeds memoryBudgetBytes().
void checkMemory(const std::string& where, const std::string& what, double bytes);

// Estimated bytes per triangle, measured on UV spheres: loading and
// cleaning a mesh (positions, welding, the sorted half-edges of the topology pass) peaked at
// 162 bytes per triangle (`penumbra info` on 33.5 M triangles: 5.4 GiB); the GL's expanded
// vertex buffers hold 3 vertices of 36 bytes per triangle (renderer.cpp GVertex). Below what was measured, so that
// what fits is not refused.
constexpr double kCleanBytesPerTriangle = 144.0;
constexpr double kGpuBytesPerTriangle = 108.0;

}  // namespace penumbra
