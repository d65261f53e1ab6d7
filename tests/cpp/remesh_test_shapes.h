#pragma once
// Generated inputs shared by the remeshing tests.
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "mesh/build_from_triangles.h"
#include "mesh/surface_mesh.h"

namespace adasculpt::test {

// A closed prism over a regular polygon of `sides` sides, its caps fanned from their centres:
// each side quad is two triangles as tall as the prism, and every side edge is a crease of
// 360 / sides degrees.
inline mesh::SurfaceMesh polygonal_prism(int sides, double radius, double height) {
  constexpr double kPi = 3.14159265358979323846;
  std::vector<std::array<double, 3>> points;
  for (double z : {0.0, height})
    for (int i = 0; i < sides; ++i)
      points.push_back({radius * std::cos(2 * kPi * i / sides), radius * std::sin(2 * kPi * i / sides), z});
  points.push_back({0, 0, 0});
  points.push_back({0, 0, height});
  std::vector<std::array<std::uint32_t, 3>> triangles;
  const auto n = static_cast<std::uint32_t>(sides);
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    triangles.push_back({i, j, n + j});
    triangles.push_back({i, n + j, n + i});
    triangles.push_back({2 * n, j, i});
    triangles.push_back({2 * n + 1, n + i, n + j});
  }
  return mesh::build_from_triangles(points, triangles);
}

}  // namespace adasculpt::test
