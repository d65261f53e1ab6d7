// The a-posteriori fidelity check of adaptive whole-mesh remeshing (issue 17): an edge whose
// midpoint or quarter points lie too far from the reference (remesher_impl.h: kFidelityMidpoint,
// kFidelityQuarter) is split (its vertex on the reference), no collapse or flip may create one,
// relaxation moves that create one are undone, and the sliver polish may not create one.
//
// The sizing field is measured on the curvature, and at a sharp edge of a coarse polyhedral input
// (a CAD part, a cube) the curvature is that of the triangles around it: large triangles, small
// curvature, long edges, and the remeshed surface cuts the crease by up to half an edge (pyramid
// at epsilon 0.01 %: Hausdorff 0.97 % of the diagonal). Lowering the sizing at creases cost too
// much elsewhere (a crease sizing term broke the CPU cap and coarse-setting monotonicity); this
// check asks the reference instead, and only where an edge can be off it.
//
// Which edges can be: both ends lie on the reference (projected), so the midpoint is off it only
// where the surface turns between them. With unit normals na, nb of the reference triangles the
// ends projected onto, a surface turning by theta between points l apart keeps the midpoint within
// (l / 2) sin(theta / 2) of it (the 90 degree crease cut symmetrically reaches it; a circular arc
// stays under half); segment_strays adds a tighter bound from the triangles' planes. Only edges
// past both bounds are measured: on the shared scans at the defaults a handful (the dragon's
// remesh keeps its figures; fandisk, a CAD part, gets 0.185 % where it had 0.245 %).
//
// A flip or a collapse is also checked from the other side, where the surface leaves the
// reference: the midpoint of the edge a flip removes, and the place of a vertex a collapse
// removes (both on the reference, up to the limits above), must lie within kFidelityOtherSide x the
// tolerance of the triangles that replace them. Edges alone never see that: a flip across a thin
// part's rim joins its two sheets with an edge inside the part, near both, and cuts the rim away
// (gen/thin_plate at epsilon 0.2 %: notches 5 tolerances deep along the whole rim, Hausdorff 1.43 %
// of the diagonal, now 0.14 %), and a collapse across a crease with features off cuts its corner
// (cgal/blob-closed at epsilon 0.05 %: 2.3 x the bound, now 0.96 x). On 210 quick runs of the
// sweep's misses, 25 were fixed and one became a miss (the geometric mean of Hausdorff over bound
// 1.33 -> 1.18), 150 passing runs still pass, and the defaults on the shared meshes are unchanged.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "geometry/triangle.h"
#include "remesh/remesher_impl.h"

namespace adasculpt::remesh {

namespace {
constexpr double kPlacedMinSin2 = 0.0109;  // sin^2 of 6 degrees: a split on the reference makes no sliver
// segment_strays: over a crease the limits shrink by (2 / 1.7) cos(theta / 2), down to half of them
// (squared here).
constexpr double kCreaseMargin2 = (2.0 / 1.7) * (2.0 / 1.7);
constexpr double kCreaseLimitScale2 = 0.25;
}  // namespace

// The largest turn between two triangles around each reference point, as 1 - cos, bounded by twice
// the widest angle of a triangle's normal from the fan's mean (exact pairs would cost the square
// of a needle fan's thousands). Needs ref_normal and the fans (build_reference).
void Remesher::Impl::build_reference_star_turns() {
  const size_t n_points = tree.points().size();
  ref_star_turn.assign(n_points, 0.0);
  for (size_t v = 0; v < n_points; ++v) {
    Vec3 sum(0.0);
    for (std::uint32_t k = ref_fan_offset[v]; k < ref_fan_offset[v + 1]; ++k) sum += ref_normal[ref_fan[k]];
    const double length = glm::length(sum);
    if (!(length > 0)) {
      ref_star_turn[v] = 2.0;  // normals all around: a turn of 180 degrees
      continue;
    }
    const Vec3 mean = sum / length;
    double min_cos = 1.0;
    for (std::uint32_t k = ref_fan_offset[v]; k < ref_fan_offset[v + 1]; ++k)
      min_cos = std::min(min_cos, glm::dot(ref_normal[ref_fan[k]], mean));
    // cos(2 alpha) = 2 cos^2(alpha) - 1, for alpha up to 90 degrees; beyond, 180 degrees.
    const double cos_turn = min_cos > 0 ? 2.0 * min_cos * min_cos - 1.0 : -1.0;
    ref_star_turn[v] = 1.0 - cos_turn;
  }
}

void Remesher::Impl::build_reference_normals() {
  const auto& pts = tree.points();
  const auto& tris = tree.triangles();
  ref_normal.resize(tris.size());
  for (size_t i = 0; i < tris.size(); ++i) {
    const auto& t = tris[i];
    const Vec3 n = glm::cross(pts[t[1]] - pts[t[0]], pts[t[2]] - pts[t[0]]);
    const double length = glm::length(n);
    ref_normal[i] = length > 0 ? n / length : Vec3(0.0);
  }
}

double Remesher::Impl::fidelity_tolerance() const {
  // Adaptive whole-mesh iterations with a current reference only: uniform remeshing has no
  // epsilon (its bound is the target length, which the edges respect by construction), and a
  // sculpting frame's region has no reference.
  if (!opt.adaptive || !has_reference || reference_stale || !whole_mesh) return 0;
  // Scaled as surface_tolerance() is: the clean-up of the input's slivers before the first
  // iteration may not reshape (Remesher::iterate). Unscaled, its repairs flipped the sharp edge
  // under a 0.5-degree cap of a box's face: the chord to the next face's far corner passed at 4
  // tolerances, and the box came out 0.86 % of the diagonal off at epsilon 0.05 % (0.11 % with
  // 2.4-degree caps, which the clean-up leaves alone).
  return tolerance_scale * std::max(opt.epsilon, kToleranceMinLengths * opt.min_length);
}

std::uint32_t Remesher::Impl::shared_reference_corner(std::uint32_t t0, std::uint32_t t1) const {
  const auto& a = tree.triangles()[t0];
  const auto& b = tree.triangles()[t1];
  std::uint32_t corner = UINT32_MAX;
  int shared = 0;
  for (const std::uint32_t i : a)
    if (i == b[0] || i == b[1] || i == b[2]) ++shared, corner = i;
  return shared == 1 ? corner : UINT32_MAX;
}

bool Remesher::Impl::segment_strays(const Point& a, std::uint32_t hint_a, const Point& b, std::uint32_t hint_b,
                                    double tolerance) const {
  const Vec3 d = b - a;
  const double l2 = glm::dot(d, d);
  // Halves shorter than the min length are the user's floor: the split pass would not split the
  // edge, so neither may a collapse or flip be refused for creating it.
  const double floor = 2 * opt.min_length;
  if (l2 < floor * floor) return false;
  double quarter2 = kFidelityQuarter * kFidelityQuarter * tolerance * tolerance;
  double middle2 = kFidelityMidpoint * kFidelityMidpoint * tolerance * tolerance;
  // Two estimates of the largest distance, against the smaller limit; without normals (a hint
  // lost), measure. (l / 2)^2 sin^2(theta / 2) = l^2 (1 - cos theta) / 8. And the planes of the
  // two reference triangles: ha, hb the heights of each end over the other's plane; along the
  // chord the distances to the planes grow linearly from 0 at its own end, and the surface of a
  // single crease between the ends is the two half-planes, so the chord is at most the smaller
  // of the two, whose largest value is ha hb / (ha + hb) (a smooth arc: twice its sagitta). The
  // second keeps edges along a crease, and the gently curved parts of a CAD model, from being
  // measured: without it the measure cost fandisk's default remesh 22 % more instructions.
  const size_t n = ref_normal.size();
  if (hint_a < n && hint_b < n) {
    const Vec3& na = ref_normal[hint_a];
    const Vec3& nb = ref_normal[hint_b];
    const double one_minus_cos = 1.0 - glm::dot(na, nb);
    // The limits hold the chord near the surface; the Hausdorff distance also asks the surface to
    // stay near the chord. Over a crease that turns by theta, the crease line lies 1 / cos(theta / 2)
    // times farther from the chord than the chord's farthest point from the two sides: sqrt 2 at a
    // right angle, 1.73 at a tetrahedron's edge (at eps 1 %, features off: edges within 1.24 eps of
    // the faces, the crease 2.29 eps from the surface). The limits keep the chord within 1.7
    // tolerances, and the target is 2: they shrink by 2 / 1.7 cos(theta / 2) where that is below 1,
    // down to half of them (a fold's turn near 180 degrees would ask for no length at all).
    // cos^2(theta / 2) = (1 + cos theta) / 2.
    const double scale2 = std::clamp(kCreaseMargin2 * (1.0 - 0.5 * one_minus_cos), kCreaseLimitScale2, 1.0);
    quarter2 *= scale2;
    middle2 *= scale2;
    // The planes' estimate holds for one crease between the ends: the hint triangles are one, or
    // neighbours across an edge. Farther apart, the surface between them may turn more than once,
    // and an end can lie on the plane of the other's triangle where that triangle does not reach
    // (cgal/tripod at epsilon 0.05 %: an edge 2 % of the diagonal long from one side of a corner
    // to the crease of two others, on the plane of one of them, its midpoint 0.53 % off the part,
    // 2.8 x the Hausdorff target). Measured.
    const auto& across = ref_adjacent[hint_a];
    const bool one_crease =
        hint_a == hint_b || across[0] == hint_b || across[1] == hint_b || across[2] == hint_b;
    const std::uint32_t corner = one_crease ? UINT32_MAX : shared_reference_corner(hint_a, hint_b);
    if (corner == UINT32_MAX) {
      if (l2 * one_minus_cos <= 8.0 * quarter2) return false;
    } else {
      // The arc's estimate trusts the two ends' normals to tell how far the surface turns between
      // them. Hint triangles that share one corner have that corner's fan between them, which may
      // turn farther and back: cgal/tripod at epsilon 0.2 % kept an edge 2.6 tolerances off the
      // part (1.25 x the Hausdorff target), from a face beside an inner corner of the part to
      // another 9 degrees from it, across the notch where two walls rise from that corner. The
      // fan's largest turn counts too.
      if (l2 * std::max(one_minus_cos, ref_star_turn[corner]) <= 8.0 * quarter2) return false;
      // Else the path over the corner bounds the chord (geometry::detour_bound): most such chords
      // pass near the corner, and this spares them the walks below.
      const auto& pts = tree.points();
      const auto& ta = tree.triangles()[hint_a];
      const auto& tb = tree.triangles()[hint_b];
      double bary[3];
      const Point a_on = geometry::closest_point_on_triangle(a, pts[ta[0]], pts[ta[1]], pts[ta[2]], bary);
      const Point b_on = geometry::closest_point_on_triangle(b, pts[tb[0]], pts[tb[1]], pts[tb[2]], bary);
      const double off = std::sqrt(std::max(glm::dot(a - a_on, a - a_on), glm::dot(b - b_on, b - b_on)));
      const double bound = geometry::detour_bound(a_on, pts[corner], b_on) + off;
      if (bound * bound <= quarter2) return false;
    }
    if (one_crease) {
      const auto& pts = tree.points();
      const auto& tris = tree.triangles();
      const Point& on_a = pts[tris[hint_a][0]];
      const Point& on_b = pts[tris[hint_b][0]];
      const double ha = std::abs(glm::dot(na, b - on_a)) + std::abs(glm::dot(na, a - on_a));
      const double hb = std::abs(glm::dot(nb, a - on_b)) + std::abs(glm::dot(nb, b - on_b));
      const double peak = ha + hb > 0 ? ha * hb / (ha + hb) : 0.0;
      if (peak * peak <= quarter2) return false;
    }
  }
  // The chord's distance from a surface that turns once between its ends (a crease) peaks where
  // it passes over the crease, anywhere along it: the midpoint alone sees half the peak when the
  // crease is near an end (an icosahedron at epsilon 0.05 %: Hausdorff 0.13 % of the diagonal
  // with edges whose midpoints were all within 0.05 %), the quarter points at least 3/4 of it.
  // Midpoint first: it strays most often.
  // The walk from the hint ends at a local minimum of the distance, which across a corner of a
  // CAD part can lie on the wrong face: a distance that passes a limit is asked of the tree too.
  // Unconfirmed, such false strays split edges that were on the surface, again and again (cgal/hole
  // at epsilon 0.01 %, min length 0.02 %, once the planes' estimate above was limited to one
  // crease: 3 x the time, a 3.9-degree triangle and 16 x the Hausdorff distance).
  auto beyond = [&](const Point& p, const geometry::TriangleTree::ClosestHit& walked, double limit2) {
    return walked.distance2 > limit2 && tree.closest_point(p, walked).distance2 > limit2;
  };
  const std::uint32_t hint = hint_a < n ? hint_a : hint_b;
  const Point mid = a + 0.5 * d, q1 = a + 0.25 * d, q3 = a + 0.75 * d;
  const geometry::TriangleTree::ClosestHit middle = closest_on_reference(mid, hint);
  if (beyond(mid, middle, middle2)) return true;
  return beyond(q1, closest_on_reference(q1, middle.triangle), quarter2) ||
         beyond(q3, closest_on_reference(q3, middle.triangle), quarter2);
}

// The guarded projection (safety.cpp) sends a vertex on a sharp edge back to where it was when
// the surface no longer passes near that place, which was on the reference after the last
// projection. Not so for a vertex the fidelity check just split in at the midpoint of an edge that
// strays: sent back there, it stayed off the surface and drew splits around it (pyramid at
// epsilon 0.01 %, 13 iterations: vertices 0.8 % of the diagonal off, then thousands of splits).
bool Remesher::Impl::strays_at(const Point& p, std::uint32_t hint) const {
  const double limit = kFidelityQuarter * fidelity_tolerance();
  return limit > 0 && closest_on_reference(p, hint).distance2 > limit * limit;
}

bool Remesher::Impl::edge_strays(Edge e, double tolerance) const {
  const Vertex a = mesh.vertex(e, 0), b = mesh.vertex(e, 1);
  return segment_strays(mesh.position(a), ref_hint[a], mesh.position(b), ref_hint[b], tolerance);
}

// The new edges of a collapse: from the target to every neighbour of the moving end(s) but the
// other end. The target carries the hint of the end that stays (either end's for a midpoint).
bool Remesher::Impl::collapse_keeps_fidelity(Halfedge h, const Point& target, bool both_ends_move,
                                             double tolerance_times) const {
  const double tolerance = tolerance_times * fidelity_tolerance();
  return !(tolerance > 0) || collapse_stays_within(h, target, both_ends_move, tolerance);
}

bool Remesher::Impl::collapse_stays_within(Halfedge h, const Point& target, bool both_ends_move,
                                           double tolerance) const {
  const Vertex v0 = mesh.from_vertex(h), v1 = mesh.to_vertex(h);
  const Halfedge o = mesh.opposite(h);
  // The third corners of the two triangles that vanish: with v1 staying, its edges to them are
  // there already (the collapse only drops v0's).
  const Vertex x = mesh.is_boundary(h) ? Vertex() : mesh.to_vertex(mesh.next(h));
  const Vertex y = mesh.is_boundary(o) ? Vertex() : mesh.to_vertex(mesh.next(o));
  const std::uint32_t hint = ref_hint[v1];
  auto fan_ok = [&](Vertex centre, Vertex other) {
    for (Halfedge out : mesh.halfedges(centre)) {
      const Vertex w = mesh.to_vertex(out);
      if (w == other || (!both_ends_move && (w == x || w == y))) continue;
      if (segment_strays(target, hint, mesh.position(w), ref_hint[w], tolerance)) return false;
    }
    return true;
  };
  if (!fan_ok(v0, v1) || (both_ends_move && !fan_ok(v1, v0))) return false;
  // The other side: the place of each end that moves stays near its new fan.
  auto stays_covered = [&](Vertex centre, Vertex other) {
    const Point& p = mesh.position(centre);
    Point corners[3];
    for (Halfedge out : mesh.halfedges(centre)) {
      if (mesh.is_boundary(out)) continue;
      const Vertex w = mesh.to_vertex(out), w2 = mesh.to_vertex(mesh.next(out));
      if (w == other || w2 == other) continue;  // one of the two triangles that vanish
      corners[0] = target, corners[1] = mesh.position(w), corners[2] = mesh.position(w2);
      if (near_triangles(p, corners, 1, kFidelityOtherSide * tolerance)) return true;
    }
    return false;
  };
  return stays_covered(v0, v1) && (!both_ends_move || stays_covered(v1, v0));
}

bool Remesher::Impl::flip_keeps_fidelity(Edge e, double tolerance_times) const {
  const double tolerance = tolerance_times * fidelity_tolerance();
  if (!(tolerance > 0)) return true;
  const Halfedge h = mesh.halfedge(e, 0), o = mesh.halfedge(e, 1);
  const Vertex a = mesh.to_vertex(o), b = mesh.to_vertex(h);
  const Vertex c = mesh.to_vertex(mesh.next(h)), d = mesh.to_vertex(mesh.next(o));
  if (segment_strays(mesh.position(c), ref_hint[c], mesh.position(d), ref_hint[d], tolerance)) return false;
  // The other side: the old edge's midpoint stays near the new triangles.
  const Point mid = 0.5 * (mesh.position(a) + mesh.position(b));
  const Point corners[6] = {mesh.position(a), mesh.position(d), mesh.position(c),
                            mesh.position(d), mesh.position(b), mesh.position(c)};
  return near_triangles(mid, corners, 2, kFidelityOtherSide * tolerance);
}

bool Remesher::Impl::near_triangles(const Point& p, const Point* corners, size_t triangles, double limit) const {
  double bary[3];
  for (size_t i = 0; i < triangles; ++i) {
    const Point q = geometry::closest_point_on_triangle(p, corners[3 * i], corners[3 * i + 1], corners[3 * i + 2], bary);
    if (glm::dot(q - p, q - p) <= limit * limit) return true;
  }
  return false;
}

// Whether an edge at v strays, v at its own place or, for fan_strayed_at, at p with that hint.
bool Remesher::Impl::fan_strayed_at(Vertex v, const Point& p, std::uint32_t hint) const {
  const double tolerance = fidelity_tolerance();
  if (!(tolerance > 0)) return false;
  for (Halfedge out : mesh.halfedges(v)) {
    const Vertex w = mesh.to_vertex(out);
    if (segment_strays(p, hint, mesh.position(w), ref_hint[w], tolerance)) return true;
  }
  return false;
}

bool Remesher::Impl::fan_strays(Vertex v) const { return fan_strayed_at(v, mesh.position(v), ref_hint[v]); }

double Remesher::Impl::fan_stray_peak2(Vertex v, const Point& p, std::uint32_t hint) const {
  double peak2 = 0;
  for (Halfedge out : mesh.halfedges(v)) {
    const Vec3 d = mesh.position(mesh.to_vertex(out)) - p;
    for (const double t : {0.25, 0.5, 0.75}) {
      const Point q = p + t * d;
      peak2 = std::max(peak2, tree.closest_point(q, closest_on_reference(q, hint)).distance2);
    }
  }
  return peak2;
}

// Relaxation slides a vertex on a sharp edge off it onto one side, and the projection keeps it
// there: the edges from it to the other side then cut the edge. The guarded projection (safety.cpp)
// catches it only where the fan turns by more than 45 degrees; an icosahedron's edges turn by 42
// (at epsilon 0.05 %: 400 straying edges after every relaxation, split again by the next
// iteration and collapsed again, Hausdorff 1.2 % of the diagonal).
// Before the relaxation no edge strayed (the split pass split them, collapses and flips made
// none), so undoing it around each straying edge always succeeds: both ends go back, then the ends
// of edges that stray because one end went back, and the corners of triangles that turned over
// against their orientation before the relaxation. Each vertex goes back at most once, so this
// ends; where it spreads to every vertex it is the whole relaxation undone. Whole-mesh iterations
// only. Returns the vertices sent back.
size_t Remesher::Impl::undo_straying_moves() {
  const double tolerance = fidelity_tolerance();
  if (!(tolerance > 0) || relaxed_from.size() != scope_vertices.size()) return 0;
  // Per vertex slot: where it was before the relaxation (0 when it did not move, 1 moved, 2 sent
  // back, 3 kept off its old place) and the queue.
  mesh::resize_scratch(fidelity_old, mesh.vertices_size());
  mesh::resize_scratch(fidelity_moved, mesh.vertices_size(), std::uint8_t(0));
  fidelity_queue.clear();
  for (size_t i = 0; i < scope_vertices.size(); ++i) {
    const Vertex v = scope_vertices[i];
    if (mesh.is_deleted(v) || relaxed_from[i] == mesh.position(v)) continue;
    fidelity_old[v.idx] = relaxed_from[i];
    fidelity_moved[v.idx] = 1;
  }
  auto send_back = [&](Vertex v) {
    if (fidelity_moved[v.idx] != 1) return;
    // Not to a place off the reference when the move put it on: the rule above assumes every edge
    // was near the reference before the relaxation, and a vertex that was not (a guard undid its
    // projection once) went back off it every iteration (cgal/double-torus-example at epsilon
    // 0.01 %: a vertex 21 tolerances off through all five iterations, the run's Hausdorff distance).
    if (strays_at(fidelity_old[v.idx], ref_hint[v]) && !strays_at(mesh.position(v), ref_hint[v])) {
      fidelity_moved[v.idx] = 3;  // kept
      return;
    }
    fidelity_moved[v.idx] = 2;
    mesh.position(v) = fidelity_old[v.idx];
    fidelity_queue.push_back(v);
  };
  auto old_position = [&](Vertex v) { return fidelity_moved[v.idx] ? fidelity_old[v.idx] : mesh.position(v); };
  for (size_t i = 0; i < scope_vertices.size(); ++i) {
    const Vertex v = scope_vertices[i];
    if (fidelity_moved[v.idx] == 0) continue;  // (deleted vertices never moved)
    if (anchored(v) && !anchor_holds(v, mesh.position(v))) send_back(v);  // (coverage.cpp)
    for (Halfedge out : mesh.halfedges(v)) {
      const Vertex w = mesh.to_vertex(out);
      if (fidelity_moved[w.idx] != 0 && w.idx < v.idx) continue;  // seen from w
      if (segment_strays(mesh.position(v), ref_hint[v], mesh.position(w), ref_hint[w], tolerance)) {
        send_back(v);
        send_back(w);
      }
    }
  }
  size_t undone = 0;
  for (size_t k = 0; k < fidelity_queue.size(); ++k) {
    const Vertex v = fidelity_queue[k];
    ++undone;
    for (Halfedge out : mesh.halfedges(v)) {
      const Vertex w = mesh.to_vertex(out);
      if (fidelity_moved[w.idx] == 1 &&
          segment_strays(mesh.position(v), ref_hint[v], mesh.position(w), ref_hint[w], tolerance))
        send_back(w);
      if (mesh.is_boundary(out)) continue;
      const Vertex w2 = mesh.to_vertex(mesh.next(out));
      if (fidelity_moved[w.idx] != 1 && fidelity_moved[w2.idx] != 1) continue;
      const Point& p = mesh.position(v);
      const Vec3 now = glm::cross(mesh.position(w) - p, mesh.position(w2) - p);
      const Vec3 before = glm::cross(old_position(w) - p, old_position(w2) - p);
      if (!(glm::dot(now, before) > 0)) {
        send_back(w);
        send_back(w2);
      }
    }
  }
  for (size_t i = 0; i < scope_vertices.size(); ++i) fidelity_moved[scope_vertices[i].idx] = 0;
  return undone;
}

// Where the fidelity check splits e: at the reference point nearest its midpoint, when the four
// triangles of the split keep the orientation of the two they replace within 60 degrees (else
// at the midpoint). A vertex left at the midpoint lies off the surface by more than the tolerance;
// when the projection that should follow is undone (a fold, a crossing), it stays there and every
// edge to it strays in turn (pyramid at epsilon 0.01 %, 10 iterations: 108 vertices 0.7 % of the
// diagonal off the surface). On the reference, the next pass splits the edges from it that still
// cross the crease, halving the distance each time.
Point Remesher::Impl::place_on_reference(Edge e, const Point& mid) const {
  const Vertex a = mesh.vertex(e, 0), b = mesh.vertex(e, 1);
  const Point& pa = mesh.position(a);
  const Point& pb = mesh.position(b);
  // On the reference triangles facing the edge's side, as the projection of a free vertex: on a
  // part thinner than the edge the nearest point may lie on the other sheet (gen/thin_plate at
  // epsilon 0.01 %: 1,783 crossing pairs before). The ends are on the reference, so the own
  // sheet is within half the edge.
  Vec3 facing(0.0);
  for (unsigned i = 0; i < 2; ++i) {
    const Halfedge h = mesh.halfedge(e, i);
    if (mesh.is_boundary(h)) continue;
    const Point& from = mesh.position(mesh.from_vertex(h));
    facing += glm::cross(mesh.position(mesh.to_vertex(h)) - from, mesh.position(mesh.to_vertex(mesh.next(h))) - from);
  }
  if (!(glm::dot(facing, facing) > 0)) return mid;
  const geometry::TriangleTree::ClosestHit hit = closest_on_reference(mid, ref_hint[a], &facing, 0.5 * glm::length(pb - pa));
  if (hit.triangle == UINT32_MAX) return mid;
  // Nor a sliver: the point on the reference may lie next to the line of another side.
  return split_halves_fair(e, hit.point, 0.5, kPlacedMinSin2) ? hit.point : mid;
}

bool Remesher::Impl::split_halves_fair(Edge e, const Point& p, double min_cos, double min_sin2) const {
  for (unsigned i = 0; i < 2; ++i) {
    const Halfedge h = mesh.halfedge(e, i);
    if (mesh.is_boundary(h)) continue;
    // The old triangle (from, to, c) and its halves (from, p, c), (p, to, c).
    const Point& from = mesh.position(mesh.from_vertex(h));
    const Point& to = mesh.position(mesh.to_vertex(h));
    const Point& c = mesh.position(mesh.to_vertex(mesh.next(h)));
    const Vec3 n = glm::cross(to - from, c - from);
    for (const Vec3& half : {glm::cross(p - from, c - from), glm::cross(to - p, c - p)}) {
      const double lengths = glm::length(n) * glm::length(half);
      if (!(lengths > 0) || glm::dot(n, half) < min_cos * lengths) return false;
    }
    if (std::min(min_angle_sin2(from, p, c), min_angle_sin2(p, to, c)) < min_sin2) return false;
  }
  return true;
}

}  // namespace adasculpt::remesh
