#include "geometry/normals.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "geometry/portable_math.h"

namespace adasculpt::geometry {

Vec3 vertex_normal(const mesh::SurfaceMesh& mesh, mesh::Vertex v) {
  const Point& p = mesh.position(v);
  Vec3 sum(0.0);
  for (mesh::Halfedge h : mesh.halfedges(v)) {
    if (mesh.is_boundary(h)) continue;
    const Vec3 u = mesh.position(mesh.to_vertex(h)) - p;
    const Vec3 w = mesh.position(mesh.to_vertex(mesh.next(h))) - p;
    const Vec3 n = glm::cross(u, w);
    const double len = glm::length(n);
    if (len == 0.0) continue;  // degenerate corner: no direction to contribute
    sum += (portable::atan2(len, glm::dot(u, w)) / len) * n;
  }
  const double len = glm::length(sum);
  return len > 0.0 ? sum / len : Vec3(0.0);
}

void vertex_normals(const mesh::SurfaceMesh& mesh, std::vector<Vec3>& out) {
  out.assign(mesh.vertices_size(), Vec3(0.0));
  for (mesh::Vertex v : mesh.vertices()) out[v.idx] = vertex_normal(mesh, v);
}

}  // namespace adasculpt::geometry
