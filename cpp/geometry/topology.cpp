#include "geometry/topology.h"

#include <cstdint>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace adasculpt::geometry {

int boundary_loops(const mesh::SurfaceMesh& mesh) {
  std::vector<std::uint8_t> seen(mesh.halfedges_size(), 0);
  int loops = 0;
  for (mesh::Halfedge h : mesh.halfedges()) {
    if (seen[h.idx] || !mesh.is_boundary(h)) continue;
    ++loops;
    // next() of a boundary halfedge stays on its boundary loop; the step cap guards against
    // a corrupted mesh looping forever.
    mesh::Halfedge g = h;
    for (size_t steps = 0; !seen[g.idx] && steps < mesh.halfedges_size(); ++steps) {
      seen[g.idx] = 1;
      g = mesh.next(g);
    }
  }
  return loops;
}

int components(const mesh::SurfaceMesh& mesh) {
  std::vector<std::uint8_t> seen(mesh.vertices_size(), 0);
  std::vector<mesh::Vertex> stack;
  int count = 0;
  for (mesh::Vertex v : mesh.vertices()) {
    if (seen[v.idx] || mesh.is_isolated(v)) continue;
    ++count;
    seen[v.idx] = 1;
    stack.push_back(v);
    while (!stack.empty()) {
      mesh::Vertex u = stack.back();
      stack.pop_back();
      for (mesh::Vertex w : mesh.vertices(u)) {
        if (seen[w.idx]) continue;
        seen[w.idx] = 1;
        stack.push_back(w);
      }
    }
  }
  return count;
}

int genus(const mesh::SurfaceMesh& mesh) {
  long used = 0;
  for (mesh::Vertex v : mesh.vertices()) used += mesh.is_isolated(v) ? 0 : 1;
  const long euler = used - static_cast<long>(mesh.n_edges()) + static_cast<long>(mesh.n_faces());
  return static_cast<int>((2L * components(mesh) - euler - boundary_loops(mesh)) / 2);
}

double bounding_box_diagonal(const mesh::SurfaceMesh& mesh) {
  bool any = false;
  Point lo(0.0), hi(0.0);
  for (mesh::Vertex v : mesh.vertices()) {
    const Point& p = mesh.position(v);
    lo = any ? glm::min(lo, p) : p;
    hi = any ? glm::max(hi, p) : p;
    any = true;
  }
  return glm::length(hi - lo);
}

}  // namespace adasculpt::geometry
