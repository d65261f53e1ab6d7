// Necks narrower than the sizing field: where the surface is a tube (or a flat strip) whose
// girth is below a few min_length, no mesh with edges of min_length exists.
//
// dragon.off has such necks (one 0.0047 around, where min_length is 0.0052). The remesher
// meshed them as tubes of three vertices around with edges of min_length along the tube: the
// loop around the tube is a triangle of edges that is no face, so none of its short edges may
// collapse (link condition) and every flip folds the surface; the slivers stayed (1.8 degrees,
// ten triangles under 10 degrees). The collapse pass reports such a loop here; the sizing is
// lowered around the neck to a third of the neck's girth, measured on the reference surface,
// so that the next iterations split the neck into rings of well-shaped triangles.
#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include <glm/geometric.hpp>

#include "geometry/triangle.h"
#include "remesh/remesher_impl.h"
#include "remesh/sizing.h"

namespace adasculpt::remesh {

namespace {
// Edges around a neck of girth P: P / kNeckVertices, a ring of that many vertices. Three (a
// triangular tube, the fewest vertices) measured best on dragon.off with the defaults: smallest
// angle 6.8 degrees, against 6.3 with four and 3.0 with five.
constexpr double kNeckVertices = 3.0;
// A neck is never sized below this fraction of min_length: the bound on the refinement where the
// reference itself pinches to a point.
constexpr double kNeckFloor = 0.125;
// The field is lowered only where the neck needs clearly shorter edges than it asks for, so a
// neck measured again (its loops keep turning up until the splits have refined it) adds nothing.
constexpr double kNeckMargin = 0.9;
// Faces on each side of a loop that make it go around a neck rather than around a small disk
// (the link of a vertex of valence three is such a loop too).
constexpr size_t kNeckSideFaces = 24;
// The reference's cross-section is followed within this many target lengths (the smallest sizing
// at the loop's corners) of the loop's centre: a neck is refined only when its girth is below
// kNeckVertices x kNeckMargin target lengths, and such a section lies within half its girth of the
// centre. The radius was this many min_length: a larger min length then found more necks, and a
// coarser setting gave more vertices (dragon at epsilon 5 %: 5,246 vertices at min length 0.2 %,
// 2,961 at 0.02 %; at epsilon 2 %: 5,241 against 3,256). With the target length, the necks found
// are the same wherever the sizing is not clamped at min_length (5,245 and 5,225).
constexpr double kNeckRadius = 1.5;
// At most this many reference triangles are gathered for one measurement.
constexpr size_t kNeckWalkLimit = 4096;
}  // namespace

// Called for a short edge that neither end may collapse into: looks for the shortest loop of
// three edges through e that bounds no face and goes around a neck, measures that neck on the
// reference, and lowers the sizing around it when the neck needs shorter edges than the field
// asks for. Whole-mesh iterations only (a sculpting frame has no reference to measure on), and
// not while mirroring (the field must stay symmetric). Returns whether the sizing was lowered.
bool Remesher::Impl::refine_neck_at(Edge e) {
  if (!opt.adaptive || !has_reference || reference_stale || mirror_axis >= 0) return false;
  const Halfedge h = mesh.halfedge(e, 0), o = mesh.halfedge(e, 1);
  const Vertex a = mesh.from_vertex(h), b = mesh.to_vertex(h);
  const Vertex x = mesh.is_boundary(h) ? Vertex() : mesh.to_vertex(mesh.next(h));
  const Vertex y = mesh.is_boundary(o) ? Vertex() : mesh.to_vertex(mesh.next(o));
  const Point& pa = mesh.position(a);
  const Point& pb = mesh.position(b);
  double best_perimeter = std::numeric_limits<double>::infinity();
  Vertex w_best;
  for (Vertex w : mesh.vertices(a)) {
    if (w == b || w == x || w == y || !mesh.find_halfedge(w, b).is_valid()) continue;
    const Point& pw = mesh.position(w);
    const double perimeter = glm::length(pb - pa) + glm::length(pw - pa) + glm::length(pw - pb);
    if (perimeter >= best_perimeter || !loop_separates_large_parts(a, b, w)) continue;
    best_perimeter = perimeter;
    w_best = w;
  }
  if (!w_best.is_valid()) return false;
  const Point& pw = mesh.position(w_best);
  const Point centre = (pa + pb + pw) / 3.0;
  // The loop lies across the neck: its normal is the neck's direction.
  const Vec3 axis = glm::cross(pb - pa, pw - pa);
  const double axis_length = glm::length(axis);
  if (!(axis_length > 0)) return false;
  // The remeshed loop is no measure of the neck: a tube of three vertices around cannot follow a
  // flat neck and comes out thinner (dragon: 0.0047 around in the input, 0.0015 after five
  // iterations), and sizing by it chased ever shorter loops down to the floor.
  const double target = std::min({sizing[a], sizing[b], sizing[w_best]});
  const double girth = reference_cross_section(centre, axis / axis_length, kNeckRadius * target,
                                               {ref_hint[a], ref_hint[b], ref_hint[w_best]});
  if (!std::isfinite(girth)) return false;
  const double size = std::max(girth / kNeckVertices, kNeckFloor * opt.min_length);
  if (size >= kNeckMargin * target) return false;
  necks.push_back({centre, size});
  lower_reference_sizing(centre, size, {ref_hint[a], ref_hint[b], ref_hint[w_best]});
  // The current vertices too, for the splits of the next iteration.
  const std::vector<Vertex> seeds = {a, b, w_best};
  for (Vertex v : seeds) sizing[v] = std::min(sizing[v], size + kGradation * glm::length(mesh.position(v) - centre));
  limit_sizing_gradation(mesh, seeds, sizing, kGradation);
  return true;
}

// Whether the loop a-b, b-w, w-a has more than kNeckSideFaces faces on both of its sides.
bool Remesher::Impl::loop_separates_large_parts(Vertex a, Vertex b, Vertex w) {
  auto on_loop = [&](Vertex v) { return v == a || v == b || v == w; };
  const Halfedge ab = mesh.find_halfedge(a, b);
  for (Halfedge start : {ab, mesh.opposite(ab)}) {
    if (mesh.is_boundary(start)) return false;
    // Faces reached from the loop's side of `start` without crossing the loop.
    std::vector<mesh::Face>& side = faces_scratch;
    side.clear();
    side.push_back(mesh.face(start));
    for (size_t i = 0; i < side.size() && side.size() <= kNeckSideFaces; ++i)
      for (Halfedge g : mesh.halfedges(side[i])) {
        if (on_loop(mesh.from_vertex(g)) && on_loop(mesh.to_vertex(g))) continue;
        const Halfedge across = mesh.opposite(g);
        if (mesh.is_boundary(across)) continue;
        const mesh::Face f = mesh.face(across);
        if (std::find(side.begin(), side.end(), f) == side.end()) side.push_back(f);
      }
    if (side.size() <= kNeckSideFaces) return false;
  }
  return true;
}

// The length of the reference surface's cross-section by the plane through `centre` with normal
// `axis`: the closed curve of the section that passes nearest to `centre`, followed over the
// reference triangles within `radius` (reached from the seed triangles over shared edges).
// Infinity when that curve is not closed within the radius: no neck there.
double Remesher::Impl::reference_cross_section(const Point& centre, const Vec3& axis, double radius,
                                               std::initializer_list<std::uint32_t> seeds) {
  const auto& tris = tree.triangles();
  const auto& pts = tree.points();
  auto height = [&](std::uint32_t p) { return glm::dot(pts[p] - centre, axis); };
  auto distance = [&](std::uint32_t t) {
    double bary[3];
    const Point q = geometry::closest_point_on_triangle(centre, pts[tris[t][0]], pts[tris[t][1]], pts[tris[t][2]], bary);
    return glm::length(q - centre);
  };
  // Triangles gathered in this measurement carry its stamp: membership in O(1), so that a fine
  // reference (thousands of triangles within the radius) costs no quadratic search.
  neck_stamp.resize(tris.size(), 0);
  if (++neck_run == 0) {
    std::fill(neck_stamp.begin(), neck_stamp.end(), 0);
    neck_run = 1;
  }
  auto gathered = [&](std::uint32_t t) { return neck_stamp[t] == neck_run; };
  std::vector<std::uint32_t>& near = neck_triangles;
  near.clear();
  auto gather = [&](std::uint32_t t) {
    if (t < tris.size() && !gathered(t) && distance(t) <= radius) {
      neck_stamp[t] = neck_run;
      near.push_back(t);
    }
  };
  for (std::uint32_t t : seeds) gather(t);
  for (size_t i = 0; i < near.size() && near.size() < kNeckWalkLimit; ++i)
    for (std::uint32_t n : ref_adjacent[near[i]])
      if (n != UINT32_MAX) gather(n);
  // The curve starts in the crossing triangle nearest to the centre.
  auto crosses = [&](std::uint32_t t) {
    const double h0 = height(tris[t][0]), h1 = height(tris[t][1]), h2 = height(tris[t][2]);
    return !((h0 > 0 && h1 > 0 && h2 > 0) || (h0 <= 0 && h1 <= 0 && h2 <= 0));
  };
  std::uint32_t start = UINT32_MAX;
  double nearest = std::numeric_limits<double>::infinity();
  for (std::uint32_t t : near)
    if (crosses(t) && distance(t) < nearest) {
      nearest = distance(t);
      start = t;
    }
  const double open = std::numeric_limits<double>::infinity();
  if (start == UINT32_MAX) return open;
  // From triangle to triangle across the crossed edges until the curve closes.
  double length = 0;
  std::uint32_t previous = UINT32_MAX, current = start;
  for (size_t step = 0; step < near.size(); ++step) {
    Point ends[2];
    int n_ends = 0;
    std::uint32_t next = UINT32_MAX;
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t p = tris[current][i], q = tris[current][(i + 1) % 3];
      const double hp = height(p), hq = height(q);
      if ((hp > 0) == (hq > 0)) continue;
      if (n_ends < 2) ends[n_ends++] = pts[p] + (hp / (hp - hq)) * (pts[q] - pts[p]);
      if (ref_adjacent[current][i] != previous) next = ref_adjacent[current][i];
    }
    if (n_ends != 2) return open;
    length += glm::length(ends[1] - ends[0]);
    // Leaving the gathered triangles (or the surface) leaves the curve open.
    if (next == UINT32_MAX || !gathered(next)) return open;
    if (next == start) return length;
    previous = current;
    current = next;
  }
  return open;
}

// Lowers the reference sizing to `size` at `centre`, growing with the gradation limit over the
// reference's edges from the corners of the given reference triangles, as far as it is below the
// stored sizing; marks the points it lowered (sizing_of_hit applies the neck there).
void Remesher::Impl::lower_reference_sizing(const Point& centre, double size,
                                            std::initializer_list<std::uint32_t> triangles) {
  const auto& tris = tree.triangles();
  const auto& pts = tree.points();
  using Item = std::pair<double, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  auto lower = [&](std::uint32_t p, double bound) {
    if (bound >= ref_sizing[p]) return;
    ref_sizing[p] = bound;
    ref_near_neck[p] = 1;
    queue.push({bound, p});
  };
  for (std::uint32_t t : triangles)
    if (t < tris.size())
      for (std::uint32_t p : tris[t]) lower(p, size + kGradation * glm::length(pts[p] - centre));
  while (!queue.empty()) {
    const auto [value, p] = queue.top();
    queue.pop();
    if (value > ref_sizing[p]) continue;  // stale entry
    for (std::uint32_t k = ref_fan_offset[p]; k < ref_fan_offset[p + 1]; ++k)
      for (std::uint32_t q : tris[ref_fan[k]]) lower(q, value + kGradation * glm::length(pts[q] - pts[p]));
  }
}

// The sizing at a reference point: interpolated over its triangle, and no larger than the
// necks ask for where the triangle is near one. A neck is often narrower than the reference
// triangles around it (dragon: 0.01 triangles across a 0.0023 wide neck), whose corners
// cannot carry its size: the interpolated value put the neck's vertices back at 2-3 times it.
double Remesher::Impl::sizing_of_hit(const geometry::TriangleTree::ClosestHit& hit) const {
  const auto& t = tree.triangles()[hit.triangle];
  double size = hit.bary[0] * ref_sizing[t[0]] + hit.bary[1] * ref_sizing[t[1]] + hit.bary[2] * ref_sizing[t[2]];
  if (!necks.empty() && (ref_near_neck[t[0]] || ref_near_neck[t[1]] || ref_near_neck[t[2]]))
    for (const Neck& n : necks) size = std::min(size, n.size + kGradation * glm::length(hit.point - n.centre));
  return size;
}

}  // namespace adasculpt::remesh
