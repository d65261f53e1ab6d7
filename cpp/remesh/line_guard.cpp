// Feature lines and the boundary kept within the tolerance of the reference (issue 17's Hausdorff
// target). A vertex with two line edges slides along its line and collapses along it, and both
// cut the line's kinks: mesh_with_border's border turns by 150 degrees at a vertex of two faces,
// and a series of collapses along it left the corner 1.9 % of the diagonal from the output at
// every epsilon. Here a kink of the reference line becomes a corner (it never slides), and a
// collapse along a line, kink or not, must keep every reference line point it spans within the
// tolerance of the new edge.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "geometry/portable_math.h"
#include "geometry/triangle.h"
#include "remesh/remesher_impl.h"

namespace adasculpt::remesh {

namespace {
// Segments a search along the reference line visits at most: a collapse spanning more reference
// segments than this (a very fine input line under a very coarse tolerance) is refused, which
// costs only coarsening there.
constexpr int kMaxLineWalk = 256;
}  // namespace

void Remesher::Impl::mark_line_kinks() {
  const std::vector<std::uint8_t> count = feature_edges_per_vertex();
  for (Vertex v : mesh.vertices())
    if (count[v.idx] == 2) vclass[v] = class_of_line_vertex(v);
}

VertexClass Remesher::Impl::class_of_line_vertex(Vertex v) const {
  Vertex ends[2];
  int n = 0;
  for (Halfedge h : mesh.halfedges(v))
    if (is_feature(mesh.edge(h)) && n < 2) ends[n++] = mesh.to_vertex(h);
  const Point& p = mesh.position(v);
  const Vec3 in = p - mesh.position(ends[0]), out = mesh.position(ends[1]) - p;
  const double turn = portable::atan2(glm::length(glm::cross(in, out)), glm::dot(in, out));
  return turn > kMaxCurveTurn ? kCorner : kFeatureLine;
}

VertexClass Remesher::Impl::class_by_lines(Vertex v) const {
  int features = 0;
  for (const Halfedge out : mesh.halfedges(v)) features += is_feature(mesh.edge(out));
  return features == 2 ? class_of_line_vertex(v) : vertex_class(features);
}

bool Remesher::Impl::is_line_kink(Vertex v) const {
  if (vclass[v] != kCorner) return false;
  int n = 0;
  for (Halfedge h : mesh.halfedges(v)) n += is_feature(mesh.edge(h));
  return n == 2;
}

namespace {
// Breadth-first search over the reference line's segments from `from` to `to` (segments meet at
// shared points), on the stack: the collapse pass is allocation-free. Calls fn(point) for each
// point where consecutive segments of the path found meet (the reference line strictly between
// the two segments); false when `to` is not within kMaxLineWalk segments.
template <class SegmentsAt, class Fn>
bool for_each_line_point_between(const std::vector<std::array<std::uint32_t, 2>>& segments,
                                 SegmentsAt&& segments_at, std::uint32_t from, std::uint32_t to, Fn&& fn) {
  if (from == to) return true;
  std::uint32_t queue[kMaxLineWalk];
  int parent[kMaxLineWalk];
  int n = 0, head = 0;
  queue[n] = from, parent[n++] = -1;
  auto seen = [&](std::uint32_t s) { return std::find(queue, queue + n, s) != queue + n; };
  int found = -1;
  while (head < n && found < 0) {
    const int at = head++;
    for (std::uint32_t end : segments[queue[at]]) {
      segments_at(end, [&](std::uint32_t s) {
        if (found >= 0 || n >= kMaxLineWalk || seen(s)) return;
        queue[n] = s, parent[n] = at;
        if (s == to) found = n;
        ++n;
      });
    }
  }
  if (found < 0) return false;
  for (int i = found; parent[i] >= 0; i = parent[i]) {
    const auto& a = segments[queue[i]];
    const auto& b = segments[queue[parent[i]]];
    fn(a[0] == b[0] || a[0] == b[1] ? a[0] : a[1]);
  }
  return true;
}
}  // namespace

bool Remesher::Impl::line_points_near_segment(std::uint32_t from, std::uint32_t to, const Point& a,
                                              const Point& b) const {
  const double limit2 = surface_tolerance() * surface_tolerance();
  const auto& pts = tree.points();
  auto segments_at = [&](std::uint32_t point, auto&& visit) {
    for (std::uint32_t k = ref_segment_offset[point]; k < ref_segment_offset[point + 1]; ++k)
      visit(ref_segment_of_point[k]);
  };
  bool near = true;
  auto check = [&](std::uint32_t point) {
    const Point q = geometry::closest_point_on_segment(pts[point], a, b);
    near = near && glm::dot(q - pts[point], q - pts[point]) <= limit2;
  };
  return for_each_line_point_between(ref_segments, segments_at, from, to, check) && near;
}

bool Remesher::Impl::line_guard_active() const {
  return has_reference && !reference_stale && whole_mesh && !ref_segments.empty();
}

// v's two line neighbours (false when v has not exactly two line edges).
bool Remesher::Impl::line_neighbours(Vertex v, Vertex ends[2]) const {
  int n = 0;
  for (Halfedge out : mesh.halfedges(v))
    if (is_feature(mesh.edge(out))) {
      if (n < 2) ends[n] = mesh.to_vertex(out);
      ++n;
    }
  return n == 2;
}

bool Remesher::Impl::line_collapse_stays_near_reference(Halfedge h) const {
  if (!line_guard_active()) return true;
  const Vertex v0 = mesh.from_vertex(h), v1 = mesh.to_vertex(h);
  Vertex ends[2];
  if (vclass[v0] == kFree || !line_neighbours(v0, ends)) return true;  // collapse_topology_ok decides
  // After the collapse the line runs u -> v1.
  const Vertex u = ends[0] == v1 ? ends[1] : ends[0];
  const Point& a = mesh.position(u);
  const Point& b = mesh.position(v1);
  const Point& p = mesh.position(v0);
  const Point q = geometry::closest_point_on_segment(p, a, b);
  if (glm::dot(q - p, q - p) > surface_tolerance() * surface_tolerance()) return false;
  // The reference line from u over v0 to v1 (through v0's segment, so that the search takes the
  // line's way between them, not a shorter one around a closed loop).
  const std::uint32_t su = nearest_line_segment(a, segment_hint[u]);
  const std::uint32_t s0 = nearest_line_segment(p, segment_hint[v0]);
  const std::uint32_t s1 = nearest_line_segment(b, segment_hint[v1]);
  return line_points_near_segment(su, s0, a, b) && line_points_near_segment(s0, s1, a, b);
}

// A line vertex slides along its line (relax_vertices) and projects onto the reference line: off
// a turn of the line that is no kink (a curve), that cuts the turn by the slide times its angle
// (fold.off's border at epsilon 0.01 %: a vertex of an 18.6-degree turn left 0.045 % of the
// diagonal from the output). A slide whose two new line edges leave a reference line point
// farther than the tolerance goes back (before_slide: per scope vertex, the place before).
size_t Remesher::Impl::undo_line_slides(const std::vector<Point>& before_slide) {
  if (!line_guard_active() || before_slide.size() != scope_vertices.size()) return 0;
  size_t undone = 0;
  for (size_t i = 0; i < scope_vertices.size(); ++i) {
    const Vertex v = scope_vertices[i];
    if (mesh.is_deleted(v) || vclass[v] != kFeatureLine || scope[v] != kActive) continue;
    const Point p = mesh.position(v);
    if (p == before_slide[i]) continue;
    Vertex ends[2];
    if (!line_neighbours(v, ends)) continue;
    const Point& a = mesh.position(ends[0]);
    const Point& b = mesh.position(ends[1]);
    const std::uint32_t sa = nearest_line_segment(a, segment_hint[ends[0]]);
    const std::uint32_t sp = nearest_line_segment(p, segment_hint[v]);
    const std::uint32_t sb = nearest_line_segment(b, segment_hint[ends[1]]);
    if (line_points_near_segment(sa, sp, a, p) && line_points_near_segment(sp, sb, p, b)) continue;
    mesh.position(v) = before_slide[i];
    segment_hint[v] = nearest_line_segment(before_slide[i], sp);
    ++undone;
  }
  return undone;
}

}  // namespace adasculpt::remesh
