#pragma once
// A fixture of the crossing guard's tests (remesh_crossing_guard_test, remesh_split_guard_test).
#include <array>
#include <cstdint>
#include <vector>

#include "mesh/build_from_triangles.h"

namespace adasculpt::test {

// A roof: the ridge a = 0, b = 1 at z = 0.5, the eaves c = 2 and d = 3 at z = 0. Flipping the
// ridge makes a valley along c-d. With `obstacle`, a flat triangle at z = 0.25 along the ridge
// (|y| <= 0.2, under the roof) that the valley's triangles cut (they are below 0.25 near x = 1),
// as do the halves of a split of the ridge at a point pushed down below it.
inline mesh::SurfaceMesh roof(bool obstacle) {
  std::vector<std::array<double, 3>> p = {{0, 0, 0.5}, {2, 0, 0.5}, {1, 1, 0}, {1, -1, 0}};
  std::vector<std::array<std::uint32_t, 3>> t = {{0, 1, 2}, {1, 0, 3}};
  if (obstacle) {
    p.push_back({0.4, 0, 0.25});
    p.push_back({1.6, -0.2, 0.25});
    p.push_back({1.6, 0.2, 0.25});
    t.push_back({4, 5, 6});
  }
  return mesh::build_from_triangles(p, t);
}

}  // namespace adasculpt::test
