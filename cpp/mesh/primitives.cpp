#include "mesh/primitives.h"

#include <array>
#include <cmath>
#include <map>

#include <glm/geometric.hpp>

#include "mesh/build_from_triangles.h"

namespace adasculpt::mesh {

namespace {
using Soup = std::vector<std::array<double, 3>>;
using Tris = std::vector<std::array<std::uint32_t, 3>>;
}  // namespace

SurfaceMesh make_icosphere(int subdivisions, double radius) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Point> pts = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                            {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  Tris tris = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
               {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
               {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (auto& p : pts) p = glm::normalize(p);
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      pts.push_back(glm::normalize(pts[a] + pts[b]));
      auto idx = static_cast<std::uint32_t>(pts.size() - 1);
      mid.emplace(key, idx);
      return idx;
    };
    Tris next;
    next.reserve(tris.size() * 4);
    for (auto& tr : tris) {
      auto ab = midpoint(tr[0], tr[1]), bc = midpoint(tr[1], tr[2]), ca = midpoint(tr[2], tr[0]);
      next.push_back({tr[0], ab, ca});
      next.push_back({tr[1], bc, ab});
      next.push_back({tr[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    tris.swap(next);
  }
  Soup soup;
  soup.reserve(pts.size());
  for (auto& p : pts) soup.push_back({p.x * radius, p.y * radius, p.z * radius});
  return build_from_triangles(soup, tris);
}

SurfaceMesh make_grid(int n, double size) {
  Soup soup;
  Tris tris;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) soup.push_back({size * (double(i) / n - 0.5), size * (double(j) / n - 0.5), 0.0});
  auto id = [n](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      // Alternate the diagonal so the grid has no preferred direction.
      if ((i + j) % 2 == 0) {
        tris.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        tris.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        tris.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
        tris.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  return build_from_triangles(soup, tris);
}

SurfaceMesh make_box(int nx, int ny, int nz, double sx, double sy, double sz) {
  // Sample the surface of the unit cube with a lattice and weld shared points by their
  // integer lattice coordinates.
  std::map<std::array<int, 3>, std::uint32_t> index;
  Soup soup;
  Tris tris;
  const int n[3] = {nx, ny, nz};
  const double s[3] = {sx, sy, sz};
  auto vertex = [&](std::array<int, 3> c) {
    auto it = index.find(c);
    if (it != index.end()) return it->second;
    std::array<double, 3> p;
    for (int k = 0; k < 3; ++k) p[k] = s[k] * (double(c[k]) / n[k] - 0.5);
    soup.push_back(p);
    auto idx = static_cast<std::uint32_t>(soup.size() - 1);
    index.emplace(c, idx);
    return idx;
  };
  for (int axis = 0; axis < 3; ++axis) {
    int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      for (int i = 0; i < n[u]; ++i)
        for (int j = 0; j < n[v]; ++j) {
          auto corner = [&](int di, int dj) {
            std::array<int, 3> c;
            c[axis] = side * n[axis];
            c[u] = i + di;
            c[v] = j + dj;
            return vertex(c);
          };
          std::uint32_t a = corner(0, 0), b = corner(1, 0), c = corner(1, 1), d = corner(0, 1);
          // (u, v, axis) is right-handed, so a->b->c is counter-clockwise seen from +axis.
          if (side == 1) {
            tris.push_back({a, b, c});
            tris.push_back({a, c, d});
          } else {
            tris.push_back({a, c, b});
            tris.push_back({a, d, c});
          }
        }
    }
  }
  return build_from_triangles(soup, tris);
}

}  // namespace adasculpt::mesh
