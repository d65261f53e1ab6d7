#include "remesh/crossing_guard.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "geometry/embedded_fan.h"
#include "geometry/self_intersections.h"
#include "geometry/triangle.h"

namespace adasculpt::remesh {

namespace {
// first_crossing refuses a candidate whose smallest angle has a sine under 1e-9 (squared here):
// collinear up to rounding, its normal is noise.
constexpr double kMinCandidateSin2 = 1e-18;
// Cells as long as this many mean edges: a face's box covers one or two cells along each axis,
// an operation's new triangles a few. One size serves the operations' queries and
// undo_crossing_moves' sweep over all pairs in a cell (whose cost grows with the faces per cell),
// so that one grid serves both: on bunny.off at the defaults, 2 or 3 for both cost within 1 % of
// 3 for the queries and 2 for the sweep (callgrind), and the outputs were the same.
constexpr double kCellEdges = 2.0;
// The work one grid allows (cells, entries and pairs of faces looked at), per face and in all: bounded work on
// inputs that defeat the grid (cgal/degtri_sliding: fans of thousands of needles in a few cells
// ran 30 s and more). The dragon at the defaults looks at about 30 pairs per face per grid.
constexpr size_t kWorkPerFace = 256;
constexpr size_t kMinWork = 1000000;

// |cross(b - a, c - a)| under this times the squared size of the pair: no direction to trust
// (surely_apart). Twice the sine of the triangle's angles at most: 1e-9 is a needle of a
// nanoradian, far above the 1e-16 of rounding and far below any triangle the remesher keeps.
constexpr double kTinyNormal = 1e-9;

bool boxes_disjoint(const Point& alo, const Point& ahi, const Point& blo, const Point& bhi) {
  return ahi.x < blo.x || alo.x > bhi.x || ahi.y < blo.y || alo.y > bhi.y || ahi.z < blo.z || alo.z > bhi.z;
}

// A fast floating-point answer for most pairs of neighbouring faces, which are (nearly) coplanar
// on flat and smooth parts: there every orientation is (nearly) zero, the exact predicates fall
// back to expansion arithmetic, and fandisk.off's remeshing took six times as long. True only
// when the two can surely not cross: both turned the same way (normals within 60 degrees) and
// their shadows on the plane across the mean normal apart by a margin far above rounding
// (a common corner or edge allowed). A 3D meeting point off the common corners would cast a
// shadow in both. Or, first and for most pairs, one triangle's free corners all strictly on one
// side of the other's plane. Otherwise the exact test decides.
// np, nq: the normals cross(p1 - p0, p2 - p0) and the same of q (the relaxation's sweep meets
// each face a dozen times and computes them once).
bool surely_apart(const Point p[3], const std::array<std::uint32_t, 3>& pid, const Vec3& np, const Point q[3],
                  const std::array<std::uint32_t, 3>& qid, const Vec3& nq) {
  int shared = 0;
  for (std::uint32_t a : pid)
    for (std::uint32_t b : qid) shared += a == b;
  // Most pairs on a curved part: the corners of one that are not shared all strictly on one
  // side of the other's plane, by a margin far above rounding.
  // (Written out: two million calls per bunny remesh, the initializer-list max and the
  // integer signs cost a third of the time.)
  auto dist2 = [&](const Point& r) { return glm::dot(r - p[0], r - p[0]); };
  const double scale2 =
      std::max(std::max(std::max(dist2(p[1]), dist2(p[2])), std::max(dist2(q[0]), dist2(q[1]))), dist2(q[2]));
  // A triangle whose normal is as small as its rounding (a needle, nearly collinear but not
  // exactly, which the callers' degenerate test leaves in) has a normal of no direction: its
  // "plane" put another face's corners on one side and called a crossing pair apart (cgal/b9_mesh
  // at epsilon 0.2 %, features 45: a needle lying in a triangle's plane, across it, after a
  // relaxation the guard did not undo). The exact test decides for such pairs.
  const double tiny2 = kTinyNormal * kTinyNormal * scale2 * scale2;
  if (!(glm::dot(np, np) > tiny2) || !(glm::dot(nq, nq) > tiny2)) return false;
  auto one_side = [&](const Vec3& n, const Point& o, const Point* r, const std::array<std::uint32_t, 3>& rid,
                      const std::array<std::uint32_t, 3>& oid) {
    const double tol2 = 1e-20 * glm::dot(n, n) * scale2;
    bool above = false, below = false;
    for (int k = 0; k < 3; ++k) {
      if (rid[k] == oid[0] || rid[k] == oid[1] || rid[k] == oid[2]) continue;
      const double side = glm::dot(n, r[k] - o);
      if (!(side * side > tol2)) return false;
      above |= side > 0;
      below |= side < 0;
    }
    return above != below;
  };
  if (shared < 2 && (one_side(np, p[0], q, qid, pid) || one_side(nq, q[0], p, pid, qid))) return true;
  const double d = glm::dot(np, nq);
  if (!(d > 0 && d * d > 0.25 * glm::dot(np, np) * glm::dot(nq, nq))) return false;
  if (shared == 2) return true;  // across an edge they can only meet by folding onto each other
  // The shadows: 2D coordinates in a frame across n, which both normals make an acute angle
  // with (so both triangles turn counter-clockwise there). The axes need not be unit vectors: a
  // linear map keeps every side and separation, and the margin is measured in the same units.
  const Vec3 n = np + nq;
  const Vec3 u = glm::cross(n, std::abs(n.x) < std::abs(n.y) ? Vec3(1, 0, 0) : Vec3(0, 1, 0));
  const Vec3 w = glm::cross(n, u);
  double px[3], py[3], qx[3], qy[3];
  for (int k = 0; k < 3; ++k) {
    px[k] = glm::dot(p[k], u), py[k] = glm::dot(p[k], w);
    qx[k] = glm::dot(q[k], u), qy[k] = glm::dot(q[k], w);
  }
  double scale = 0;
  for (int k = 0; k < 3; ++k)
    scale = std::max({scale, std::abs(px[k] - px[0]), std::abs(py[k] - py[0]), std::abs(qx[k] - px[0]),
                      std::abs(qy[k] - py[0])});
  const double margin = 1e-9 * scale * scale;
  // A separating line through an edge of either shadow: the other triangle's corners beyond it,
  // but for the corners the two share (on the line, which allows them).
  auto separated_by_edges = [&](const double* ax, const double* ay, const std::array<std::uint32_t, 3>& aid,
                                const double* bx, const double* by, const std::array<std::uint32_t, 3>& bid) {
    const double area = (ax[1] - ax[0]) * (ay[2] - ay[0]) - (ay[1] - ay[0]) * (ax[2] - ax[0]);
    if (!(area > margin)) return false;  // not counter-clockwise by a margin: no answer here
    for (int e = 0; e < 3; ++e) {
      const int i = e, j = (e + 1) % 3;
      bool beyond = true;
      for (int k = 0; k < 3 && beyond; ++k) {
        if (bid[k] == aid[i] || bid[k] == aid[j]) continue;
        const double side = (ax[j] - ax[i]) * (by[k] - ay[i]) - (ay[j] - ay[i]) * (bx[k] - ax[i]);
        beyond = side < -margin;
      }
      if (beyond) return true;
    }
    return false;
  };
  return separated_by_edges(px, py, pid, qx, qy, qid) || separated_by_edges(qx, qy, qid, px, py, pid);
}

Vec3 normal_of(const Point p[3]) { return glm::cross(p[1] - p[0], p[2] - p[0]); }

// Two faces across an edge folded flat onto each other: their normals (np, nq as above) opposite
// within kFlatFoldAngle. Exactly coplanar such a pair crosses (geometry/self_intersections.h), but
// on a flat part of the input, where every vertex lies on one plane up to rounding, the exact test
// says the pair meets along its edge only, whichever way the rounding went. The relaxation makes
// such folds when it slides a vertex past its neighbours there, and the next split pass turns them
// into crossings: its midpoint lies off the edge by rounding, so the halves of a triangle next to
// the fold cross the folded face (gen twist_coarse, a 0.01-thick plate twisted half a turn, at
// epsilon 0.01 %: 21 pairs after the third split pass, 5 in the output). Any angle far above
// rounding and far below a fold a curved part makes serves.
constexpr double kFlatFoldAngle = 1e-4;  // radians
bool folded_flat(const std::array<std::uint32_t, 3>& pid, const Vec3& np, const std::array<std::uint32_t, 3>& qid,
                 const Vec3& nq) {
  int shared = 0;
  for (std::uint32_t a : pid)
    for (std::uint32_t b : qid) shared += a == b;
  if (shared != 2) return false;
  const double d = glm::dot(np, nq);
  const double cos_limit = 1.0 - 0.5 * kFlatFoldAngle * kFlatFoldAngle;
  return d < 0 && d * d >= cos_limit * cos_limit * glm::dot(np, np) * glm::dot(nq, nq);
}

// The guard's pair test: a crossing, or a flat fold (above). Both faces non-degenerate.
bool faces_cross(const Point p[3], const std::array<std::uint32_t, 3>& pid, const Vec3& np, const Point q[3],
                 const std::array<std::uint32_t, 3>& qid, const Vec3& nq) {
  return folded_flat(pid, np, qid, nq) || geometry::faces_intersect(p, pid, q, qid);
}
bool faces_cross(const Point p[3], const std::array<std::uint32_t, 3>& pid, const Point q[3],
                 const std::array<std::uint32_t, 3>& qid) {
  return faces_cross(p, pid, normal_of(p), q, qid, normal_of(q));
}

std::array<std::uint32_t, 3> corners(const mesh::SurfaceMesh& mesh, mesh::Face f) {
  mesh::Vertex c[3];
  mesh.face_vertices(f, c);
  return {c[0].idx, c[1].idx, c[2].idx};
}
}  // namespace

void CrossingGuard::start(const SurfaceMesh& mesh) {
  active_ = true;
  in_region_ = false;
  reset_budget();
  build_grid(mesh);
}

void CrossingGuard::resume(const SurfaceMesh& mesh) {
  if (!grid_.built() || in_region_ || (!active_ && mesh.faces_size() != kept_face_slots_)) return start(mesh);
  active_ = true;
  reset_budget();
  work_left_ = kMinWork + kWorkPerFace * mesh.n_faces();
}

void CrossingGuard::reset_budget() {
  contain_inherited_ = false;
  renewals_left_ = kRenewals;
  spent_ = false;
}

bool CrossingGuard::renew_budget(const SurfaceMesh& mesh) {
  if (renewals_left_ == 0) {
    spent_ = true;
    return false;
  }
  --renewals_left_;
  build_grid(mesh);
  return true;
}

void CrossingGuard::build_grid(const SurfaceMesh& mesh) {
  const auto* hc = mesh.halfedge_connectivity_data();
  const Point* pos = mesh.positions().data();
  double sum = 0;
  size_t n = 0;
  for (Edge e : mesh.edges()) {
    sum += glm::length(pos[hc[e.idx << 1].to.idx] - pos[hc[(e.idx << 1) | 1u].to.idx]);
    ++n;
  }
  if (n == 0) return;
  // The mean edge: where the collapses that follow make faces larger, the cells grow with them
  // (FaceGrid::insert). Cells of the target length would hold hundreds of a fine input's faces.
  grid_.build(mesh, kCellEdges * sum / static_cast<double>(n));
  work_left_ = kMinWork + kWorkPerFace * mesh.n_faces();
}

void CrossingGuard::flipped(const SurfaceMesh& mesh, Edge e) {
  if (!active()) return;
  grid_.insert(mesh, mesh.face(mesh.halfedge(e, 0)));
  grid_.insert(mesh, mesh.face(mesh.halfedge(e, 1)));
}

// The faces near the candidates are gathered once for all of them (an operation's new
// triangles are neighbours: their boxes overlap), then each is read once from the mesh.
namespace {
// Whether the faces with corners a and b crossed at the positions `before` (per vertex slot).
bool crossed_before(const PlacesBefore& before, const std::array<std::uint32_t, 3>& a,
                    const std::array<std::uint32_t, 3>& b) {
  const Point pa[3] = {before[a[0]], before[a[1]], before[a[2]]}, pb[3] = {before[b[0]], before[b[1]], before[b[2]]};
  if (geometry::collinear(pa[0], pa[1], pa[2]) || geometry::collinear(pb[0], pb[1], pb[2])) return false;
  return faces_cross(pa, a, pb, b);
}
}  // namespace

CrossingGuard::Crossing CrossingGuard::first_crossing(const SurfaceMesh& mesh, const Candidate* ts, size_t n,
                                                      Vertex replaced0, Vertex replaced1, Face skip0, Face skip1,
                                                      const PlacesBefore* before) {
  Crossing crossing;
  if (n == 0) return crossing;
  Point lo = ts[0].p[0], hi = ts[0].p[0];
  shapes_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const Point* p = ts[i].p;
    // No orientation: never created. Nor one collinear up to rounding (a smallest angle's sine
    // under 1e-9): its normal is rounding noise, and the quick tests below trust normals. A split
    // placed on a straight feature line between two of its vertices made such triangles
    // (cgal/b9_mesh at eps 0.01 %, features 45: sines of 1e-14, and 18 crossing pairs among them
    // that the guard passed).
    if (geometry::collinear(p[0], p[1], p[2]) || geometry::min_angle_sin2(p[0], p[1], p[2]) < kMinCandidateSin2) {
      crossing.found = true;
      crossing.triangle = i;
      return crossing;
    }
    // Each candidate's box and normal once: every near face is compared with each candidate.
    shapes_[i] = {glm::min(p[0], glm::min(p[1], p[2])), glm::max(p[0], glm::max(p[1], p[2])), normal_of(p)};
    lo = glm::min(lo, shapes_[i].lo), hi = glm::max(hi, shapes_[i].hi);
  }
  fans_after_.clear();
  // Every face the gather finds costs one unit more, charged up front. A spent budget is renewed
  // (a grid at the current mean edge: a coarsening pass outgrows the cells it started with); once
  // the renewals are spent too, the operation is refused.
  for (;;) {
    if (spent_) {
      crossing.found = true;
      return crossing;
    }
    near_.clear();
    if (grid_.gather(lo, hi, near_, work_left_) && work_left_ >= near_.size()) break;
    renew_budget(mesh);
  }
  work_left_ -= near_.size();
  const auto* hc = mesh.halfedge_connectivity_data();
  const mesh::Halfedge* fh = mesh.face_halfedge_data();
  const std::uint8_t* fdel = mesh.face_deleted_data();
  const Point* pos = mesh.positions().data();
  for (const Face g : near_) {
    if (g.idx >= mesh.faces_size() || fdel[g.idx] || g == skip0 || g == skip1) continue;
    const Halfedge h0 = fh[g.idx], h1 = hc[h0.idx].next, h2 = hc[h1.idx].next;
    const std::array<std::uint32_t, 3> ids = {hc[h0.idx].to.idx, hc[h1.idx].to.idx, hc[h2.idx].to.idx};
    if (ids[0] == replaced0.idx || ids[1] == replaced0.idx || ids[2] == replaced0.idx || ids[0] == replaced1.idx ||
        ids[1] == replaced1.idx || ids[2] == replaced1.idx)
      continue;  // a face the operation rewrites
    const Point q[3] = {pos[ids[0]], pos[ids[1]], pos[ids[2]]};
    const Point qlo = glm::min(q[0], glm::min(q[1], q[2])), qhi = glm::max(q[0], glm::max(q[1], q[2]));
    if (boxes_disjoint(qlo, qhi, lo, hi)) continue;  // (the grid's boxes are rounded outwards, or stale)
    bool checked_degenerate = false;
    Vec3 nq;
    for (size_t i = 0; i < n; ++i) {
      const Candidate& t = ts[i];
      if (g == t.face || boxes_disjoint(qlo, qhi, shapes_[i].lo, shapes_[i].hi) ||
          shared_fan_embedded(mesh, t.ids, ids, ts, n, replaced0, replaced1, skip0, skip1))
        continue;
      if (!checked_degenerate) {
        checked_degenerate = true;
        if (geometry::collinear(q[0], q[1], q[2])) break;  // left out, as the self-intersection count does
        nq = normal_of(q);
      }
      if (surely_apart(t.p, t.ids, shapes_[i].normal, q, ids, nq) || !faces_cross(t.p, t.ids, shapes_[i].normal, q, ids, nq))
        continue;
      if (crossed_already(mesh, g, q, ids, shapes_[i].lo, shapes_[i].hi, replaced0, replaced1, skip0, skip1)) {
        if (contain_inherited_) continue;  // the next candidate may meet g beyond the old crossing
        break;
      }
      if (before && crossed_before(*before, t.ids, ids)) continue;
      crossing.found = true;
      crossing.triangle = i;
      crossing.face = g;
      return crossing;
    }
  }
  return crossing;
}

// With contain_inherited_, the new triangle t may only meet g where a replaced face met it: t's
// box and g's must overlap within the box over the overlaps of g's box with those of the replaced
// faces that cross it.
bool CrossingGuard::crossed_already(const SurfaceMesh& mesh, Face g, const Point q[3],
                                    const std::array<std::uint32_t, 3>& ids, const Point& t_lo, const Point& t_hi,
                                    Vertex replaced0, Vertex replaced1, Face skip0, Face skip1) const {
  const Point g_lo = glm::min(q[0], glm::min(q[1], q[2])), g_hi = glm::max(q[0], glm::max(q[1], q[2]));
  Point met_lo(std::numeric_limits<double>::infinity()), met_hi(-std::numeric_limits<double>::infinity());
  auto add_if_crossing_g = [&](Face f) {
    if (!f.is_valid() || f == g) return;
    if (!contain_inherited_ && met_lo.x <= met_hi.x) return;  // one is enough
    const std::array<std::uint32_t, 3> c = corners(mesh, f);
    const Point p[3] = {mesh.positions()[c[0]], mesh.positions()[c[1]], mesh.positions()[c[2]]};
    if (geometry::collinear(p[0], p[1], p[2]) || !faces_cross(p, c, q, ids)) return;
    met_lo = glm::min(met_lo, glm::max(g_lo, glm::min(p[0], glm::min(p[1], p[2]))));
    met_hi = glm::max(met_hi, glm::min(g_hi, glm::max(p[0], glm::max(p[1], p[2]))));
  };
  for (const Vertex r : {replaced0, replaced1})
    if (r.is_valid())
      for (Face f : mesh.faces(r)) add_if_crossing_g(f);
  add_if_crossing_g(skip0);
  add_if_crossing_g(skip1);
  if (!contain_inherited_) return met_lo.x <= met_hi.x;
  const Point meet_lo = glm::max(g_lo, t_lo), meet_hi = glm::min(g_hi, t_hi);
  return glm::all(glm::greaterThanEqual(meet_lo, met_lo)) && glm::all(glm::lessThanEqual(meet_hi, met_hi));
}

void CrossingGuard::collapse_candidates(const SurfaceMesh& mesh, Halfedge h, const Point& target,
                                        bool both_ends_move) {
  const Vertex v0 = mesh.from_vertex(h), v1 = mesh.to_vertex(h);
  candidates_.clear();
  auto add_fan = [&](Vertex centre, Vertex other) {
    for (Halfedge out : mesh.halfedges(centre)) {
      if (mesh.is_boundary(out)) continue;
      const Vertex w = mesh.to_vertex(out), w2 = mesh.to_vertex(mesh.next(out));
      if (w == other || w2 == other) continue;  // one of the two triangles that vanish
      candidates_.push_back({{target, mesh.position(w), mesh.position(w2)}, {v1.idx, w.idx, w2.idx}, Face()});
    }
  };
  add_fan(v0, v1);
  if (both_ends_move) add_fan(v1, v0);
}

bool CrossingGuard::fan_embedded_after_collapse(const SurfaceMesh& mesh, Halfedge h, const Point& target,
                                                bool both_ends_move, Vertex w) {
  collapse_candidates(mesh, h, target, both_ends_move);
  return fan_embedded_after(mesh, w.idx, candidates_.data(), candidates_.size(), mesh.from_vertex(h),
                            both_ends_move ? mesh.to_vertex(h) : Vertex(), Face(), Face());
}

bool CrossingGuard::collapse_crosses(const SurfaceMesh& mesh, Halfedge h, const Point& target, bool both_ends_move) {
  if (!active()) return false;
  const Vertex v0 = mesh.from_vertex(h), v1 = mesh.to_vertex(h);
  collapse_candidates(mesh, h, target, both_ends_move);
  if (first_crossing(mesh, candidates_.data(), candidates_.size(), v0, both_ends_move ? v1 : Vertex(), Face(),
                     Face())
          .found)
    return true;
  // The new fan against itself: triangles meeting only at the survivor may still cross, unless
  // the survivor's fan after the collapse is embedded (all of them are in it).
  if (remembered_fan_embedded_after(mesh, v1.idx, candidates_.data(), candidates_.size(), v0,
                                    both_ends_move ? v1 : Vertex(), Face(), Face()))
    return false;
  for (size_t i = 0; i < candidates_.size(); ++i)
    for (size_t j = i + 1; j < candidates_.size(); ++j)
      if (faces_cross(candidates_[i].p, candidates_[i].ids, candidates_[j].p, candidates_[j].ids))
        return true;
  return false;
}

bool CrossingGuard::flip_crosses(const SurfaceMesh& mesh, Edge e) {
  if (!active()) return false;
  const Halfedge h = mesh.halfedge(e, 0), o = mesh.halfedge(e, 1);
  const Vertex a = mesh.to_vertex(o), b = mesh.to_vertex(h);
  const Vertex c = mesh.to_vertex(mesh.next(h)), d = mesh.to_vertex(mesh.next(o));
  const Point &pa = mesh.position(a), &pb = mesh.position(b), &pc = mesh.position(c), &pd = mesh.position(d);
  // The two new triangles share the edge cd; the flip's own test keeps them from folding.
  const Candidate t[2] = {{{pa, pd, pc}, {a.idx, d.idx, c.idx}, Face()}, {{pd, pb, pc}, {d.idx, b.idx, c.idx}, Face()}};
  return first_crossing(mesh, t, 2, Vertex(), Vertex(), mesh.face(h), mesh.face(o)).found;
}

bool CrossingGuard::split_crosses(const SurfaceMesh& mesh, Edge e, const Point& p) {
  if (!active()) return false;
  // The new vertex's id: the next slot (no vertex of the mesh has it, which is all that matters).
  const std::uint32_t v = static_cast<std::uint32_t>(mesh.vertices_size());
  Candidate t[4];
  size_t n = 0;
  Face replaced[2];
  for (unsigned i = 0; i < 2; ++i) {
    const Halfedge h = mesh.halfedge(e, i);
    if (mesh.is_boundary(h)) continue;
    const Vertex a = mesh.from_vertex(h), b = mesh.to_vertex(h), c = mesh.to_vertex(mesh.next(h));
    const Point &pa = mesh.position(a), &pb = mesh.position(b), &pc = mesh.position(c);
    t[n++] = {{pa, p, pc}, {a.idx, v, c.idx}, Face()};
    t[n++] = {{p, pb, pc}, {v, b.idx, c.idx}, Face()};
    replaced[i] = mesh.face(h);
  }
  return first_crossing(mesh, t, n, Vertex(), Vertex(), replaced[0], replaced[1]).found;
}

CrossingGuard::Crossing CrossingGuard::fan_crossing(const SurfaceMesh& mesh, Vertex v,
                                                    const PlacesBefore* before) {
  candidates_.clear();
  if (!active()) return {};
  for (Face f : mesh.faces(v)) {
    const std::array<std::uint32_t, 3> c = corners(mesh, f);
    candidates_.push_back({{mesh.positions()[c[0]], mesh.positions()[c[1]], mesh.positions()[c[2]]}, c, f});
  }
  return first_crossing(mesh, candidates_.data(), candidates_.size(), Vertex(), Vertex(), Face(), Face(), before);
}

// Nine pairs in ten whose boxes touch are neighbours with a common corner: one test of that
// corner's fan (geometry/embedded_fan.h) clears all of its pairs at once, at the positions the
// sweep sees (fan_embedded_ is per call).
bool CrossingGuard::share_an_embedded_fan(const SurfaceMesh& mesh, const std::array<std::uint32_t, 3>& a,
                                          const std::array<std::uint32_t, 3>& b) {
  for (const std::uint32_t v : a) {
    if (v != b[0] && v != b[1] && v != b[2]) continue;
    std::uint8_t& known = fan_embedded_[v];
    if (known == kUnknown) known = geometry::fan_surely_embedded(mesh, Vertex(v)) ? kEmbedded : kNotShown;
    if (known == kEmbedded) return true;
  }
  return false;
}

// The first round checks every pair of touching boxes in one sweep over the grid's cells: a
// search around each of the tens of thousands of moved vertices cost four times as much
// (memory-bound); the later rounds search around the few vertices sent back.
// Only new crossings count: a pair that crossed before the moves (an input that crosses itself,
// its crossings multiplied by the splits) keeps its moves, which often untangle it; sending
// them back froze cgal/corner_poly.off's crossing corner (1,616 new pairs at epsilon 0.5 %). For
// the same reason a face that turns over without crossing anything stays (bunny.off's two
// crossing pairs are untangled that way).
size_t CrossingGuard::undo_crossing_moves(SurfaceMesh& mesh, const std::vector<Point>& places_before) {
  const PlacesBefore before(places_before);
  // Each face's corners once, in face order: the sweep below meets every face several times.
  face_corners_.resize(mesh.faces_size());
  face_normals_.resize(mesh.faces_size());
  face_degenerate_.resize(mesh.faces_size());
  moved_face_.assign(mesh.faces_size(), 0);
  bool any = false;
  for (Face f : mesh.faces()) any = note_face(mesh, before, f, f.idx) || any;
  if (!any) return 0;
  fan_embedded_.assign(mesh.vertices_size(), kUnknown);
  start(mesh);
  to_undo_.clear();
  auto wanted = [&](Face f, Face g) {
    return (moved_face_[f.idx] || moved_face_[g.idx]) && !face_degenerate_[f.idx] && !face_degenerate_[g.idx] &&
           !share_an_embedded_fan(mesh, face_corners_[f.idx], face_corners_[g.idx]);
  };
  grid_.for_each_overlapping_pair(work_left_, wanted, [&](Face f, Face g) {
    list_if_crossing_anew(mesh, before, face_corners_[f.idx], face_normals_[f.idx], face_corners_[g.idx],
                          face_normals_[g.idx]);
    return true;
  });
  return send_back(mesh, before);
}

bool CrossingGuard::note_face(const SurfaceMesh& mesh, const PlacesBefore& before, Face f, size_t key) {
  const Point* pos = mesh.positions().data();
  const std::array<std::uint32_t, 3> c = corners(mesh, f);
  face_corners_[key] = c;
  const Point p[3] = {pos[c[0]], pos[c[1]], pos[c[2]]};
  face_normals_[key] = normal_of(p);
  face_degenerate_[key] = geometry::collinear(p[0], p[1], p[2]);
  moved_face_[key] = p[0] != before[c[0]] || p[1] != before[c[1]] || p[2] != before[c[2]];
  return moved_face_[key];
}

void CrossingGuard::list_if_crossing_anew(const SurfaceMesh& mesh, const PlacesBefore& before,
                                          const std::array<std::uint32_t, 3>& cf, const Vec3& nf,
                                          const std::array<std::uint32_t, 3>& cg, const Vec3& ng) {
  const Point* pos = mesh.positions().data();
  const Point pf[3] = {pos[cf[0]], pos[cf[1]], pos[cf[2]]}, pg[3] = {pos[cg[0]], pos[cg[1]], pos[cg[2]]};
  if (surely_apart(pf, cf, nf, pg, cg, ng) || !faces_cross(pf, cf, nf, pg, cg, ng)) return;
  if (crossed_before(before, cf, cg)) return;  // not the moves' doing
  list_moved_corners(mesh, before, cf);
  list_moved_corners(mesh, before, cg);
}

void CrossingGuard::list_moved_corners(const SurfaceMesh& mesh, const PlacesBefore& before,
                                       const std::array<std::uint32_t, 3>& c) {
  for (std::uint32_t w : c)
    if (mesh.positions()[w] != before[w]) to_undo_.push_back(Vertex(w));
}

size_t CrossingGuard::send_back(SurfaceMesh& mesh, const PlacesBefore& before, bool stop_when_spent) {
  size_t undone = 0;
  crossed_fans_.clear();
  for (;;) {
    to_check_.clear();
    for (const Vertex w : to_undo_) {
      if (mesh.position(w) == before[w.idx]) continue;  // listed twice, or back already
      mesh.position(w) = before[w.idx];
      grid_.insert_fan(mesh, w);
      to_check_.push_back(w);
      ++undone;
    }
    if (to_check_.empty() || (stop_when_spent && spent_)) break;
    // The fans of the vertices sent back, against their neighbours' new places, and again those
    // that crossed in the last round: only the first crossing of each was resolved there (a fan
    // sent back across two moved triangles kept the second: a twisted thin plate at epsilon
    // 0.01 % ended with 8 crossing pairs).
    to_check_.insert(to_check_.end(), crossed_fans_.begin(), crossed_fans_.end());
    crossed_fans_.clear();
    to_undo_.clear();
    for (const Vertex v : to_check_) {
      const Crossing crossing = fan_crossing(mesh, v, &before);
      if (stop_when_spent && spent_) break;  // (found, but not shown)
      if (!crossing.found) continue;
      // A region leaves a degenerate triangle (no face crossed) to fix_bad_faces, as the sweep does.
      if (in_region_ && !crossing.face.is_valid()) continue;
      list_moved_corners(mesh, before, candidates_[crossing.triangle].ids);
      if (crossing.face.is_valid()) list_moved_corners(mesh, before, corners(mesh, crossing.face));
      crossed_fans_.push_back(v);
    }
  }
  return undone;
}

}  // namespace adasculpt::remesh
