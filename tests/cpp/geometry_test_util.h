#pragma once
// Shared helpers of the geometry tests: procedural meshes the primitives do not cover and
// brute-force references for the accelerated queries.
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "mesh/build_from_triangles.h"
#include "mesh/surface_mesh.h"

namespace adasculpt::test {

inline constexpr double kPi = 3.14159265358979323846;

// Counts and the bits of every live position: what undo/redo must restore exactly.
inline uint64_t fingerprint(const mesh::SurfaceMesh& m) {
  uint64_t h = 1469598103934665603ull;  // FNV-1a
  auto mix = [&h](const void* p, size_t n) {
    const unsigned char* b = static_cast<const unsigned char*>(p);
    for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  };
  const uint64_t counts[3] = {m.n_vertices(), m.n_edges(), m.n_faces()};
  mix(counts, sizeof counts);
  for (mesh::Vertex v : m.vertices()) mix(&m.position(v), sizeof(Point));
  return h;
}

// The vertex with the largest z (the grab tests pick the sphere's top there).
inline Point highest_point(const mesh::SurfaceMesh& m) {
  Point best(0, 0, -1e300);
  for (mesh::Vertex v : m.vertices())
    if (m.position(v).z > best.z) best = m.position(v);
  return best;
}

// An open cylinder of radius r around the z axis: `around` segments, `rings` rows of
// quads split into two triangles, rows as tall as the segments are wide.
inline mesh::SurfaceMesh make_cylinder(double r, int around, int rings) {
  std::vector<std::array<double, 3>> pts;
  std::vector<std::array<std::uint32_t, 3>> tris;
  const double pi = 3.14159265358979323846;
  const double dz = 2 * pi * r / around;
  for (int j = 0; j <= rings; ++j)
    for (int i = 0; i < around; ++i)
      pts.push_back({r * std::cos(2 * pi * i / around), r * std::sin(2 * pi * i / around), j * dz});
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(j * around + (i % around)); };
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < around; ++i) {
      tris.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      tris.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return mesh::build_from_triangles(pts, tris);
}

// Closest point on triangle abc by exhaustion: the plane projection when it falls inside,
// else the best of the three edges.
inline Point brute_closest_on_triangle(const Point& p, const Point& a, const Point& b, const Point& c) {
  auto seg = [&](const Point& u, const Point& v) {
    Vec3 d = v - u;
    double t = glm::dot(d, d) > 0 ? std::fmin(1.0, std::fmax(0.0, glm::dot(p - u, d) / glm::dot(d, d))) : 0.0;
    return u + t * d;
  };
  Point best = seg(a, b);
  for (const Point& q : {seg(b, c), seg(c, a)})
    if (glm::dot(q - p, q - p) < glm::dot(best - p, best - p)) best = q;
  Vec3 n = glm::cross(b - a, c - a);
  double n2 = glm::dot(n, n);
  if (n2 > 0) {
    Point q = p - (glm::dot(p - a, n) / n2) * n;
    double u = glm::dot(glm::cross(c - b, q - b), n) / n2, v = glm::dot(glm::cross(a - c, q - c), n) / n2;
    if (u >= 0 && v >= 0 && u + v <= 1 && glm::dot(q - p, q - p) < glm::dot(best - p, best - p)) best = q;
  }
  return best;
}

inline std::string shared_mesh(const std::string& name) {
  return std::string(ADASCULPT_SHARED_MESHES_DIR) + "/" + name;
}
// A mesh of the CGAL corpus (scripts/fetch-cgal-meshes.sh) in its cache: $ADASCULPT_DATA, else
// ~/.cache/adasculpt. A plain clone has none; tests on it skip with a message.
inline std::string cgal_mesh(const std::string& name) {
  const char* data = std::getenv("ADASCULPT_DATA");
  const char* home = std::getenv("HOME");
  const std::string root = data ? data : (home ? std::string(home) + "/.cache/adasculpt" : std::string(".cache"));
  return root + "/cgal/data/meshes/" + name;
}
inline std::string test_mesh(const std::string& name) {
  return std::string(ADASCULPT_SOURCE_DIR) + "/tests/data/meshes/" + name;
}

}  // namespace adasculpt::test
