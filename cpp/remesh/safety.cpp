// Geometric safety of the remeshing operations (issue 17 item 2), beyond the per-face orientation
// tests of the passes: the projection keeps a vertex on its own sheet (reference.cpp, with the fan
// normal measured here), and at sharp edges, marked as features or not, collapses and relaxation
// moves must keep the surface within a tolerance of the reference. Whole-mesh iterations only: a
// sculpting frame's region has no reference (its surface is the reference), so the per-frame path
// pays nothing but a flag test in the relaxation.
#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "geometry/triangle.h"
#include "remesh/remesher_impl.h"

namespace adasculpt::remesh {

Remesher::Impl::FanShape Remesher::Impl::fan_shape(Vertex v) const {
  const auto* hc = mesh.halfedge_connectivity_data();
  const Halfedge* vh = mesh.vertex_halfedge_data();
  const Point* pos = mesh.positions().data();
  const Point& p = pos[v.idx];
  Vec3 normal(0.0);
  FanCreaseTest crease;
  for_each_outgoing(hc, vh, v, [&](Halfedge h) {
    if (!hc[h.idx].face.is_valid()) return crease.gap();
    const Vec3 n = glm::cross(pos[hc[h.idx].to.idx] - p, pos[hc[hc[h.idx].next.idx].to.idx] - p);
    normal += n;
    crease.add(n);
  });
  return {normal, crease.creased()};
}

double Remesher::Impl::surface_tolerance() const {
  const double tolerance = opt.adaptive ? std::max(opt.epsilon, kToleranceMinLengths * opt.min_length)
                                        : kToleranceTargetLengths * opt.target_length;
  return tolerance_scale * tolerance;
}

// The collapse's new triangles (the fan of each moving end, without the two triangles that
// vanish) must stay near the reference where a moving end sits on a sharp edge: their centroids
// within the tolerance of it, and the place the end was (on the reference after a projection)
// within the tolerance of them. Each collapse alone passes the per-face tests of
// collapse_geometry_ok while a series of them walks the surface away: the 0.2-degree sides of
// gen/sliver_cylinder are "degenerate" to the input clean-up, whose collapses of their short ring
// edges took the 48-gon cross-section down to a hexagon (Hausdorff 2.5 % of the diagonal,
// crossing pairs); with features off, collapses across a sharp edge cut it. On smooth surface
// the sizing field bounds the error already (the same tests there changed nothing measurable on
// the hard cases and cost the smooth meshes vertices, angles and time). Only with a current
// reference (whole-mesh iterations): a sculpting frame's region has none.
bool Remesher::Impl::collapse_stays_near_reference(Halfedge h, const Point& target, bool both_ends_move) const {
  if (!has_reference || reference_stale || !whole_mesh) return true;
  const Vertex v0 = mesh.from_vertex(h), v1 = mesh.to_vertex(h);
  const double limit2 = surface_tolerance() * surface_tolerance();
  // A vertex of a feature line or of the border moves along it: where the line turns (a border's
  // 45 degree corner on a flat part), the collapse cuts the corner off. The line from the target
  // to the vertex's other neighbour on it must pass within the tolerance of where the vertex was
  // (degtri_sliding.off at eps 2%: both 45 degree corners cut, Hausdorff 6 % of the diagonal).
  auto line_ok = [&](Vertex centre, Vertex other) {
    if (vclass[centre] != kFeatureLine) return true;
    for (Halfedge out : mesh.halfedges(centre)) {
      const Vertex w = mesh.to_vertex(out);
      if (w == other || !is_feature(mesh.edge(out))) continue;
      const Vec3 d = mesh.position(centre) - geometry::closest_point_on_segment(mesh.position(centre), target, mesh.position(w));
      if (glm::dot(d, d) > limit2) return false;
    }
    return true;
  };
  auto fan_ok = [&](Vertex centre, Vertex other) {
    if (!line_ok(centre, other)) return false;
    if (!fan_shape(centre).creased) return true;
    const Point old = mesh.position(centre);
    double old_distance2 = std::numeric_limits<double>::infinity();
    std::uint32_t hint = ref_hint[centre];
    for (Halfedge out : mesh.halfedges(centre)) {
      if (mesh.is_boundary(out)) continue;
      const Vertex w = mesh.to_vertex(out), w2 = mesh.to_vertex(mesh.next(out));
      if (w == other || w2 == other) continue;
      const Point& a = mesh.position(w);
      const Point& b = mesh.position(w2);
      const geometry::TriangleTree::ClosestHit hit = closest_on_reference((target + a + b) / 3.0, hint);
      if (hit.distance2 > limit2) return false;
      hint = hit.triangle;
      double bary[3];
      const Point q = geometry::closest_point_on_triangle(old, target, a, b, bary);
      old_distance2 = std::min(old_distance2, glm::dot(q - old, q - old));
    }
    return old_distance2 <= limit2;
  };
  return fan_ok(v0, v1) && (!both_ends_move || fan_ok(v1, v0));
}

void Remesher::Impl::remember_positions() {
  relaxed_from.resize(scope_vertices.size());
  const Point* pos = mesh.positions().data();
  for (size_t i = 0; i < scope_vertices.size(); ++i) relaxed_from[i] = pos[scope_vertices[i].idx];
}

// With features off a sharp edge is just strongly curved surface: tangential relaxation slides
// its vertices off it onto one side, the projection keeps them there, and the triangles from
// them to the other side cut the edge (fandisk at epsilon 0.5 %: Hausdorff 1.39 % of the
// diagonal). The place a vertex on a sharp edge left was on the reference (projected in the last
// iteration): the surface must still pass within the tolerance of it. Such a vertex goes back,
// unless going back would turn one of its triangles over. Free vertices only: feature-line
// vertices slide along their line and project onto it.
// The fan shapes come from the relaxation's own face terms (keep_fan_shapes): a walk around
// every fan here cost a tenth of a whole-mesh remesh of the dragon.
size_t Remesher::Impl::project_vertices_guarded() {
  creased_moved.clear();
  for (size_t i = 0; i < scope_vertices.size(); ++i) {
    const Vertex v = scope_vertices[i];
    if (mesh.is_deleted(v) || !movable(v)) continue;
    const FanShape& shape = fan_shapes[i];
    if (vclass[v] != kFree || glm::dot(shape.normal, shape.normal) == 0) {
      project(v);  // feature vertices onto their lines; a degenerate fan measured on its own
      continue;
    }
    project(v, shape.normal);
    if (shape.creased && relaxed_from[i] != mesh.position(v)) creased_moved.push_back(static_cast<std::uint32_t>(i));
  }
  const double limit2 = surface_tolerance() * surface_tolerance();
  size_t undone = 0;
  for (const std::uint32_t i : creased_moved) {
    const Vertex v = scope_vertices[i];
    const Point old = relaxed_from[i];
    const Point now = mesh.position(v);
    double distance2 = std::numeric_limits<double>::infinity();
    bool folds = false;
    for (Halfedge out : mesh.halfedges(v)) {
      if (mesh.is_boundary(out)) continue;
      const Point& a = mesh.position(mesh.to_vertex(out));
      const Point& b = mesh.position(mesh.to_vertex(mesh.next(out)));
      double bary[3];
      const Point q = geometry::closest_point_on_triangle(old, now, a, b, bary);
      distance2 = std::min(distance2, glm::dot(q - old, q - old));
      folds = folds || !(glm::dot(glm::cross(a - now, b - now), glm::cross(a - old, b - old)) > 0);
    }
    if (folds || distance2 <= limit2 || strays_at(old, ref_hint[v])) continue;
    mesh.position(v) = old;
    ++undone;
  }
  return undone;
}

void Remesher::Impl::undo_crossing_moves() {
  if (relaxed_from.size() != scope_vertices.size()) return;
  if (!whole_mesh) {
    if (region_crossing_guard) undo_region_crossing_moves();
    return;
  }
  mesh::resize_scratch(before_move, mesh.vertices_size());
  const Point* pos = mesh.positions().data();
  std::copy(pos, pos + mesh.vertices_size(), before_move.begin());  // (masked vertices stay)
  for (size_t i = 0; i < scope_vertices.size(); ++i) before_move[scope_vertices[i].idx] = relaxed_from[i];
  crossing_guard.undo_crossing_moves(mesh, before_move);
}

}  // namespace adasculpt::remesh
