// Memory before allocating: a scene that needs more memory than this
// process may allocate is refused with one line before it is built, not killed half-way by
// std::bad_alloc or the OOM killer.
#pragma once

#include <string>

namespace penumbra {

// Bytes this process may still allocate: the smaller of physical memory and, where set, the
// address-space and data limits (`ulimit -v`, `ulimit -d`) less what the process already uses.
double memoryBudgetBytes();

// Throws Error(where, "<what> needs about <N> MiB, more than the <M> MiB this process may
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
