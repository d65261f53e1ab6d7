#include "remesh/feature_sectors.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "remesh/remesher.h"

namespace adasculpt::remesh {

std::vector<std::uint8_t> feature_edge_marks(const SurfaceMesh& mesh, double feature_angle_deg) {
  // The remesher marks its mesh when it is made and takes the marks away when it goes: make one on
  // a copy and read them. Its other options do not change the marks.
  SurfaceMesh copy = mesh;
  RemeshOptions options = default_options_for(copy);
  options.feature_angle_deg = feature_angle_deg;
  Remesher remesher(copy, options);
  const auto marks = copy.get_edge_property<std::uint8_t>("remesh:feature");
  std::vector<std::uint8_t> out(mesh.edges_size(), 0);
  for (mesh::Edge e : copy.edges()) out[e.idx] = marks[e];
  return out;
}

namespace {
// The angle at v between the edges to a and b (degrees).
double corner_angle_deg(const Point& v, const Point& a, const Point& b) {
  const Vec3 u = a - v, w = b - v;
  return std::atan2(glm::length(glm::cross(u, w)), glm::dot(u, w)) * 180.0 / M_PI;
}
}  // namespace

FeatureSector smallest_feature_sector(const SurfaceMesh& mesh, const std::vector<std::uint8_t>& edge_marks) {
  FeatureSector best;
  auto marked = [&](mesh::Halfedge h) { return edge_marks[SurfaceMesh::edge(h).idx] != 0; };
  for (mesh::Vertex v : mesh.vertices()) {
    const mesh::Halfedge first = mesh.halfedge(v);
    if (!first.is_valid()) continue;
    // Start the walk at a marked spoke so that every sector is summed whole.
    mesh::Halfedge start = first;
    int marks = 0;
    for (mesh::Halfedge h : mesh.halfedges(v))
      if (marked(h)) {
        if (marks++ == 0) start = h;
      }
    if (marks < 2) continue;
    const Point& p = mesh.position(v);
    double sector = 0;
    bool open = true;  // the sector since the last marked spoke has faces only
    mesh::Halfedge h = start;
    do {
      // The face between spoke h and the next spoke clockwise, cw_rotated(h) = next(opposite(h)).
      const mesh::Halfedge next = mesh.cw_rotated(h);
      if (!mesh.face(mesh.opposite(h)).is_valid()) {
        open = false;  // a boundary gap: the marked spokes on its sides bound no sector through it
      } else {
        sector += corner_angle_deg(p, mesh.position(mesh.to_vertex(h)), mesh.position(mesh.to_vertex(next)));
      }
      if (marked(next)) {
        if (open && sector < best.angle_deg) best = {sector, v};
        sector = 0;
        open = true;
      }
      h = next;
    } while (h != start);
  }
  return best;
}

}  // namespace adasculpt::remesh
