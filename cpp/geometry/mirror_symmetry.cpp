#include "geometry/mirror_symmetry.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "geometry/position_index.h"

namespace adasculpt::geometry {

std::vector<mesh::Vertex> find_mirror_map(const mesh::SurfaceMesh& mesh, int axis) {
  std::vector<mesh::Vertex> image;
  if (axis < 0 || axis > 2 || mesh.n_vertices() == 0) return image;
  // The cheap test first (most scanned meshes fail it): the extent along the axis is symmetric.
  double lo = mesh.position(*mesh.vertices().begin())[axis], hi = lo;
  for (mesh::Vertex v : mesh.vertices()) {
    lo = std::min(lo, mesh.position(v)[axis]);
    hi = std::max(hi, mesh.position(v)[axis]);
  }
  if (lo != -hi) return image;

  // Open addressing over a power-of-two table at most half full: one flat allocation, no nodes
  // (a std::unordered_map took 32 ms for 164k vertices, this about a tenth of that).
  size_t size = 16;
  while (size < 2 * mesh.n_vertices()) size *= 2;
  const size_t mask = size - 1;
  constexpr std::uint32_t kEmpty = UINT32_MAX;
  std::vector<std::uint32_t> table(size, kEmpty);
  for (mesh::Vertex v : mesh.vertices()) {
    const Point& p = mesh.position(v);
    size_t slot = position_hash(p) & mask;
    for (; table[slot] != kEmpty; slot = (slot + 1) & mask)
      if (same_position(mesh.position(mesh::Vertex(table[slot])), p)) return image;  // two vertices at one point
    table[slot] = v.idx;
  }
  image.assign(mesh.vertices_size(), mesh::Vertex());
  for (mesh::Vertex v : mesh.vertices()) {
    Point p = mesh.position(v);
    p[axis] = -p[axis];
    size_t slot = position_hash(p) & mask;
    for (; table[slot] != kEmpty; slot = (slot + 1) & mask)
      if (same_position(mesh.position(mesh::Vertex(table[slot])), p)) break;
    if (table[slot] == kEmpty) return {};
    image[v.idx] = mesh::Vertex(table[slot]);
  }
  return image;
}

bool is_mirror_symmetric(const mesh::SurfaceMesh& mesh, int axis) {
  const std::vector<mesh::Vertex> image = find_mirror_map(mesh, axis);
  if (image.empty()) return false;
  // The mirror image of the halfedge a->b of a triangle is M(b)->M(a) in the image triangle (a
  // reflection reverses orientation), with the image of the third corner.
  for (mesh::Face f : mesh.faces()) {
    const mesh::Halfedge h = mesh.halfedge(f);
    const mesh::Vertex a = mesh.from_vertex(h), b = mesh.to_vertex(h), c = mesh.to_vertex(mesh.next(h));
    const mesh::Halfedge g = mesh.find_halfedge(image[b.idx], image[a.idx]);
    if (!g.is_valid() || mesh.is_boundary(g) || mesh.from_vertex(mesh.prev(g)) != image[c.idx]) return false;
  }
  return true;
}

}  // namespace adasculpt::geometry
