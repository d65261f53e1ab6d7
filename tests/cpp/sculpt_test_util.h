#pragma once
// Scenes for the sculpting tests: several disjoint copies of a mesh.
#include <array>
#include <cstdint>
#include <vector>

#include "io/load_mesh.h"
#include "mesh/build_from_triangles.h"
#include "mesh/primitives.h"

namespace adasculpt::test {

// `copies` disjoint copies of an icosphere(4) (radius 1), side by side 3 apart along x.
inline mesh::SurfaceMesh sphere_copies(int copies) {
  const io::PolygonSoup one = io::soup_from_mesh(mesh::make_icosphere(4));
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<uint32_t, 3>> tris;
  for (int c = 0; c < copies; ++c) {
    const uint32_t base = uint32_t(points.size());
    for (auto p : one.points) points.push_back({p[0] + 3.0 * c, p[1], p[2]});
    for (auto t : one.triangles) tris.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  return mesh::build_from_triangles(points, tris);
}

}  // namespace adasculpt::test
