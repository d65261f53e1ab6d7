// Thin parts: where the distance through the solid to the opposite sheet (the local thickness)
// is below the sizing, edges as long as the sizing bridge the two sheets, the flips and the
// relaxation fold one sheet onto the other, and the part is crumpled. The sizing there is
// clamped to a fraction of the thickness, measured once per reference build by a ray from each
// reference vertex into the solid, so the part is kept with edges that fit it.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "remesh/remesher_impl.h"

namespace adasculpt::remesh {

namespace {
// The edges at a thin part are at most this many times its thickness: a rim gets a row of
// triangles across, none bridging the sheets. Measured on dragon.off (fins down to 0.02 % of the
// diagonal thick): at epsilon 1 % / 5 %, Hausdorff 2.28 / 10.3 % of the diagonal without the
// clamp, 1.09 / 1.23 % with 1.0 (22,903 / 22,567 vertices instead of 6,702 / 5,245); 0.5 gave
// 0.65 / 0.88 % for 38k vertices. At the defaults: 62,019 vertices without, 64,141 with 1.0,
// about 72k with 0.5.
constexpr double kThicknessEdges = 1.0;
// Never below this fraction of min_length (the necks' floor too): the bound of the refinement
// where the surface pinches to nothing.
constexpr double kThicknessFloor = 0.125;
// The clamp is set at the reference's vertices and interpolated over its triangles: at a vertex
// whose edges are longer than this many times the clamped length, the interpolation would carry
// it far from the thin part (the 8 corners of a box-shaped plate would size the whole plate).
constexpr double kThicknessReach = 4.0;

// +1 when the faces turn their right-hand normals outwards (positive signed volume), else -1.
double outward_sign(const SurfaceMesh& mesh) {
  double volume = 0;
  for (mesh::Face f : mesh.faces()) {
    Vertex c[3];
    mesh.face_vertices(f, c);
    volume += glm::dot(mesh.position(c[0]), glm::cross(mesh.position(c[1]), mesh.position(c[2])));
  }
  return volume < 0 ? -1.0 : 1.0;
}
}  // namespace

void Remesher::Impl::clamp_sizing_to_thickness(const std::vector<Vertex>& vertices) {
  if (!has_reference) return;
  const double inward = -outward_sign(mesh);
  const double floor = kThicknessFloor * opt.min_length;
  for (Vertex v : vertices) {
    if (vclass[v] != kFree) continue;
    // The area-weighted normal of the fan (the angle-weighted one of geometry/normals.h, with its
    // arc tangents, cost half as much again as the rays on bunny.off).
    const Point& p = mesh.position(v);
    Vec3 n(0.0);
    for (Halfedge h : mesh.halfedges(v))
      if (!mesh.is_boundary(h))
        n += glm::cross(mesh.position(mesh.to_vertex(h)) - p, mesh.position(mesh.to_vertex(mesh.next(h))) - p);
    const double length = glm::length(n);
    if (!(length > 0)) continue;
    n /= length;
    // Started a hair inside, so that the vertex's own triangles are not the hit.
    const Vec3 dir = inward * n;
    const double start = 1e-6 * sizing[v];
    // Only a part thinner than the sizing matters: the probe ends there, and the tree prunes
    // every box beyond it.
    const double reach = sizing[v] / kThicknessEdges;
    const geometry::TriangleTree::RayHit hit = tree.intersect_ray(p + start * dir, dir, reach);
    if (!hit.hit) continue;
    const double fitting = kThicknessEdges * (hit.t + start);
    const double size = std::max(fitting, floor);
    if (!(size < sizing[v])) continue;
    // The reach is judged on the length the thickness asks for, before the floor: which vertices
    // are clamped must not depend on min_length, or a larger one would clamp more of them.
    double longest = 0;
    for (Halfedge h : mesh.halfedges(v)) longest = std::max(longest, glm::length(mesh.position(mesh.to_vertex(h)) - p));
    if (longest <= kThicknessReach * fitting) sizing[v] = size;
  }
}

}  // namespace adasculpt::remesh
