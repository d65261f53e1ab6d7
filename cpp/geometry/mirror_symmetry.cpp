#include "geometry/mirror_symmetry.h"

#include <cstdint>
#include <cstring>
#include <unordered_map>

namespace adasculpt::geometry {

namespace {
// A position as its exact bit pattern, with -0 read as +0 (the plane's vertices may carry either).
struct PositionKey {
  std::uint64_t bits[3];
  bool operator==(const PositionKey& o) const {
    return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
  }
};
struct PositionKeyHash {
  size_t operator()(const PositionKey& k) const {
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (std::uint64_t b : k.bits) h = (h ^ b) * 0xff51afd7ed558ccdull, h ^= h >> 32;
    return size_t(h);
  }
};
PositionKey key_of(Point p) {
  PositionKey k;
  for (int i = 0; i < 3; ++i) {
    const double c = p[i] == 0 ? 0.0 : p[i];
    std::memcpy(&k.bits[i], &c, sizeof c);
  }
  return k;
}
}  // namespace

std::vector<mesh::Vertex> find_mirror_map(const mesh::SurfaceMesh& mesh, int axis) {
  std::vector<mesh::Vertex> image;
  if (axis < 0 || axis > 2) return image;
  std::unordered_map<PositionKey, mesh::Vertex, PositionKeyHash> at;
  at.reserve(mesh.n_vertices());
  for (mesh::Vertex v : mesh.vertices())
    if (!at.emplace(key_of(mesh.position(v)), v).second) return image;  // two vertices at one point
  image.assign(mesh.vertices_size(), mesh::Vertex());
  for (mesh::Vertex v : mesh.vertices()) {
    Point p = mesh.position(v);
    p[axis] = -p[axis];
    const auto it = at.find(key_of(p));
    if (it == at.end()) return {};
    image[v.idx] = it->second;
  }
  // Connectivity: the mirror image of the halfedge a->b of a triangle is Mb->Ma in the image
  // triangle (a reflection reverses orientation), with the image of the third corner.
  for (mesh::Face f : mesh.faces()) {
    const mesh::Halfedge h = mesh.halfedge(f);
    const mesh::Vertex a = mesh.from_vertex(h), b = mesh.to_vertex(h), c = mesh.to_vertex(mesh.next(h));
    const mesh::Halfedge g = mesh.find_halfedge(image[b.idx], image[a.idx]);
    if (!g.is_valid() || mesh.is_boundary(g) || mesh.from_vertex(mesh.prev(g)) != image[c.idx]) return {};
  }
  return image;
}

}  // namespace adasculpt::geometry
