// Small meshes shared by the geometry tests.
#pragma once

#include "geometry/mesh.h"

namespace penumbra::geo::test {

// Unit cube centred at the origin: vertices 0-3 are the square (-,-) (+,-) (+,+) (-,+) in
// (x, y) at z = -0.5, vertices 4-7 the same at z = +0.5. Counter-clockwise seen from outside.
inline TriangleMesh cube() {
  TriangleMesh m;
  m.positions = {{-0.5f, -0.5f, -0.5f}, {0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, -0.5f}, {-0.5f, 0.5f, -0.5f},
                 {-0.5f, -0.5f, 0.5f},  {0.5f, -0.5f, 0.5f},  {0.5f, 0.5f, 0.5f},  {-0.5f, 0.5f, 0.5f}};
  m.triangles = {{0, 3, 2}, {0, 2, 1},   // -z
                 {4, 5, 6}, {4, 6, 7},   // +z
                 {0, 1, 5}, {0, 5, 4},   // -y
                 {3, 7, 6}, {3, 6, 2},   // +y
                 {0, 4, 7}, {0, 7, 3},   // -x
                 {1, 2, 6}, {1, 6, 5}};  // +x
  return m;
}

// Three quads sharing the spine (0,0,0)-(0,1,0), each with its own copy of the spine vertices.
inline TriangleMesh book() {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0},  {0, 1, 0},
                 {0, 0, 1}, {0, 1, 1}, {0, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {-1, 1, 0}};
  m.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 6, 7}, {4, 7, 5}, {8, 9, 11}, {8, 11, 10}};
  return m;
}

}  // namespace penumbra::geo::test
