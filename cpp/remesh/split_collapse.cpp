// Edge-length passes of a remeshing iteration: split edges longer than 4/3 L, collapse edges
// shorter than 4/5 L (Botsch & Kobbelt 2004 thresholds, L from the sizing field).
#include <algorithm>
#include <cstdint>
#include <cmath>
#include <cstring>

#include <glm/geometric.hpp>

#include "geometry/triangle.h"
#include "remesh/remesher_impl.h"

namespace adasculpt::remesh {

namespace {
constexpr double kCollapseFactor = 4.0 / 5.0;
constexpr int kMaxSplitPasses = 10;
constexpr int kRegionSplitPasses = 2;
// A region call (a sculpting frame) collapses at most this share of its scope; the short edges
// left over are found again by the next frame's call. The first frame of a grab on a remeshed scan
// collapsed 2,230 edges of its 10.6k-vertex region (the sizing measured on the current surface is
// coarser than the reference's): 13.5M instructions, the largest frame of the pull.
constexpr size_t kRegionCollapseShare = 8;
// Squared length / squared collapse threshold below which an edge may collapse to its midpoint.
constexpr double kMidpointCollapseRatio = 0.25;
// sin^2 of one degree: no collapse leaves a triangle flatter than that (collapse_geometry_ok).
constexpr double kDegenerateSin2 = 3.0459e-4;

// Called for every edge of the scope by both passes: read straight from the flat arrays, and
// inlined (g++ -O2 kept it out of line, 5 % of a sculpting frame's instructions in calls).
[[gnu::always_inline]] inline double squared_length(const SurfaceMesh& m, Edge e) {
  const auto* hc = m.halfedge_connectivity_data();
  const Point* pos = m.positions().data();
  const Point& a = pos[hc[e.idx << 1].to.idx];
  const Point& b = pos[hc[(e.idx << 1) | 1u].to.idx];
  const double dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
  return dx * dx + dy * dy + dz * dz;
}

// A candidate edge and its squared length / squared threshold, as one sort key: the ratio's
// float bits above (non-negative floats order as their bit patterns), the edge index below, so
// equal ratios order by index. Integers sort with plain comparisons, where (ratio, edge) pairs
// took a comparison function (libc++'s sort in wasm: 5 % of a smooth stamp's profile before, 4 %).
std::uint32_t float_bits(double ratio) {
  const float r = static_cast<float>(ratio);
  std::uint32_t bits;
  std::memcpy(&bits, &r, sizeof bits);
  return bits;
}
// Ascending ratio: the collapse pass, shortest first.
std::uint64_t ascending_key(double ratio, Edge e) { return (std::uint64_t(float_bits(ratio)) << 32) | e.idx; }
// Descending ratio, equal ratios by ascending index: the split pass, longest first.
std::uint64_t descending_key(double ratio, Edge e) { return (std::uint64_t(~float_bits(ratio)) << 32) | e.idx; }
Edge key_edge(std::uint64_t key) { return Edge(static_cast<mesh::Index>(key & 0xffffffffu)); }
double key_ratio(std::uint64_t key) {
  const std::uint32_t bits = static_cast<std::uint32_t>(key >> 32);
  float r;
  std::memcpy(&r, &bits, sizeof r);
  return r;
}

}  // namespace

// A whole-mesh iteration's scope is every edge (a region call gathers its scope's edges in its
// classification walk, iterate_region).
void Remesher::Impl::gather_all_edges() {
  scope_edges.clear();
  for (Edge e : mesh.edges())
    if (in_scope(e)) scope_edges.push_back(e);  // all but those at masked vertices
}

Vertex Remesher::Impl::split_edge(Edge e, const Point& p) {
  Vertex a = mesh.vertex(e, 1), b = mesh.vertex(e, 0);  // halfedge(e,0) runs a -> b
  const double size = 0.5 * (sizing[a] + sizing[b]);
  const std::uint8_t was_feature = feature[e];
  const std::uint32_t hint = ref_hint[a];
  const std::uint32_t seg_hint = segment_hint[vclass[a] != kFree ? a : b];
  Vertex v = mesh.split(e, p);
  if (mask.is_valid()) mask[v] = 0.5f * (mask[a] + mask[b]);  // partly masked ends (full ones are never split)
  // The old edge now runs a -> v; the new edge v -> b inherits its feature flag.
  Halfedge vb = mesh.find_halfedge(v, b);
  feature[mesh.edge(vb)] = was_feature;
  vclass[v] = was_feature ? kFeatureLine : kFree;
  scope[v] = kActive;
  ref_hint[v] = hint;
  segment_hint[v] = seg_hint;
  sizing[v] = size;
  if (has_reference && !reference_stale) {
    std::uint32_t h = hint;
    sizing[v] = reference_sizing_at(p, &h);
    ref_hint[v] = h;
  }
  scope_vertices.push_back(v);
  note_fan_changed(v);
  return v;
}

size_t Remesher::Impl::split_with_mirror(Edge e, bool far_from_reference) {
  const double limit = kSplitFactor * target_length(e);
  // Not long: split already, as an image (or the half of a split edge that kept its index), or
  // split for the fidelity check if it still strays.
  const bool not_long = squared_length(mesh, e) <= limit * limit;
  if (not_long && !(far_from_reference && edge_strays(e, fidelity_tolerance()))) return 0;
  const Point mid = 0.5 * (mesh.position(mesh.vertex(e, 0)) + mesh.position(mesh.vertex(e, 1)));
  // While the crossing guard is on (every split but those of a pass that refines wholesale, see
  // run_iteration), a split whose halves would cross the surface is left out: the midpoint lies
  // off the edge by rounding (crossing_guard.h). gen twist_coarse at epsilon 0.01 %, 5 iterations:
  // 25 pairs after the last split pass, 15 in the output, all at a flat part's vertices, where
  // an edge of a fold lay on two faces of the other side up to rounding.
  // The halving of a pass that refines wholesale goes unchecked, as its first pass does (the
  // guard is on there only for the fidelity splits, and for the long edges that stray, below):
  // checking each of its splits was 8 % of the instructions of cgal/ChineseDragon-10kv at epsilon
  // 0.01 % (214k splits).
  // A long edge whose midpoint strays from the reference: measured once, for both questions, and
  // only while the guard is on (nothing can be checked or placed without it).
  const bool long_and_straying =
      !not_long && far_from_reference && crossing_guard.active() && edge_strays(e, fidelity_tolerance());
  const bool unchecked = refining_wholesale && !not_long && !long_and_straying;
  if (!unchecked && crossing_guard.split_crosses(mesh, e, mid)) return 0;
  // A long edge whose midpoint strays from the reference (a chord across a crease features do not
  // mark) gets its vertex on the reference too, as a fidelity split does, while the guard can check
  // the placed fan (not in a pass that refines wholesale). At the midpoint, a vertex whose later
  // projection crosses the surface is sent back there by every iteration's undo_crossing_moves and
  // stays off the surface to the end: cgal/part.off at epsilon 0.05 %, min length 0.2 %, features
  // off, kept one 3 tolerances off from the third iteration (Hausdorff 0.30 % of the diagonal,
  // bound 0.2 %; 0.13 % now).
  if (mirror_axis < 0) {
    if (not_long || long_and_straying)
      split_placed_on_reference(e, mid);
    else
      split_edge(e, mid);
    return 1;
  }
  const Edge image = mirror_edge(e);
  if (image.is_valid() && image != e && crossing_guard.split_crosses(mesh, image, mirrored(mid))) return 0;
  const size_t first = image.is_valid() && image != e ? split_shared_triangle(e, image) : 0;
  const Vertex v = split_edge(e, mid);
  if (mirror_axis < 0) return 1;  // symmetry lost: a plain split
  if (image == e) {  // in or across the plane: the midpoint is on the plane, exactly
    mirror[v] = v;
    return 1;
  }
  const Vertex w = split_edge(image, mirrored(mid));
  mirror[v] = w;
  mirror[w] = v;
  return first + 2;
}

// A fidelity split at the reference point nearest the midpoint (place_on_reference), kept only
// when the crossing guard finds the new fan crossing nothing; else back at the midpoint, which
// split_with_mirror found crossing nothing. On a part thinner than the edge the placed point may
// push the fan through the other sheet (the CGAL elk, femur, diplodocus at epsilon 0.01-0.05 %:
// 11 of 4,964 sweep runs with 3 to 27 new crossing pairs came from such splits).
// split_long_edges starts the guard before the first of these splits.
void Remesher::Impl::split_placed_on_reference(Edge e, const Point& mid) {
  const Point placed = place_on_reference(e, mid);
  const Vertex v = split_edge(e, placed);
  if (placed == mid || !crossing_guard.fan_crosses(mesh, v)) return;
  mesh.position(v) = mid;
  note_fan_changed(v);
}

// An edge from the plane to a vertex off it and its image can be two sides of one triangle (its
// own image: a, a', p with p on the plane). Splitting both would leave a quad (a, a', w, v) whose
// diagonal can't be symmetric; splitting the triangle's third side, across the plane, first
// puts the two edges in different triangles. Returns the splits done.
size_t Remesher::Impl::split_shared_triangle(Edge e, Edge image) {
  for (unsigned i = 0; i < 2; ++i) {
    const Halfedge h = mesh.halfedge(e, i);
    if (mesh.is_boundary(h)) continue;
    const Halfedge n = mesh.next(h), p = mesh.prev(h);
    Edge across;
    if (mesh.edge(n) == image)
      across = mesh.edge(p);
    else if (mesh.edge(p) == image)
      across = mesh.edge(n);
    else
      continue;
    const Point mid = 0.5 * (mesh.position(mesh.vertex(across, 0)) + mesh.position(mesh.vertex(across, 1)));
    const Vertex u = split_edge(across, mid);  // its own image: the midpoint is on the plane
    mirror[u] = u;
    return 1;
  }
  return 0;
}

size_t Remesher::Impl::split_long_edges() {
  size_t splits = 0;
  if (whole_mesh) gather_all_edges();  // (a region call gathered its scope's edges already)
  // A sculpting frame does bounded work: two passes (a long edge halves, then its halves may
  // halve once more); later frames continue. A whole-mesh iteration splits until done.
  const int passes = whole_mesh ? kMaxSplitPasses : kRegionSplitPasses;
  // At most doubling the region per frame, whatever the sizing says (a stray vertex far away
  // makes every edge to it "long"): the work of one frame stays proportional to the region.
  // A whole-mesh iteration stops at the vertex budget (budget.cpp).
  const size_t max_splits = whole_mesh ? splits_allowed() : scope_vertices.size();
  // An edge between two held vertices with a triangle outside the scope is the border of a
  // region: splitting it halves that outside triangle, which no pass of a region call may improve
  // (its third corner is untouched): a refining brush left 11-13 % of the triangles just outside
  // its radius under 30 degrees that way (now 2-4 %). Held vertices are the ring a deformation
  // leaves in place (a brush's outer ring, a grab's first fixed ring), so no frame stretches such
  // an edge; it is split once a later region holds both its triangles.
  auto on_region_border = [&](Edge e) {
    if (scope[mesh.vertex(e, 0)] != kHeld || scope[mesh.vertex(e, 1)] != kHeld) return false;
    for (unsigned i = 0; i < 2; ++i) {
      Halfedge h = mesh.halfedge(e, i);
      if (!mesh.is_boundary(h) && scope[mesh.to_vertex(mesh.next(h))] == kOutside) return true;
    }
    return false;
  };
  // scope_edges stays every edge of the scope: the splits only add edges (each split edge keeps
  // its index for one half), and the added ones are the slots from first_new_edge on. The
  // collapse pass then needs no second walk over every fan of the region.
  const mesh::Index first_new_edge = static_cast<mesh::Index>(mesh.edges_size());
  const std::vector<Edge>* to_check = &scope_edges;
  // Edges not long but off the reference by more than this are split too (fidelity.cpp); they sort
  // after the long ones (ratio at most 1). Zero in region calls.
  const double fidelity = fidelity_tolerance();
  refining_wholesale = whole_mesh && !crossing_guard.active();  // (run_iteration stopped it)
  for (int pass = 0; pass < passes && splits < max_splits; ++pass) {
    candidates.clear();
    size_t long_ones = 0;
    for (Edge e : *to_check) {
      double limit = kSplitFactor * target_length(e);
      double l2 = squared_length(mesh, e);
      if (l2 > limit * limit) {
        if (on_region_border(e)) continue;
        ++long_ones;
      } else if (!(fidelity > 0 && edge_strays(e, fidelity))) {
        continue;
      }
      candidates.push_back(descending_key(l2 / (limit * limit), e));
    }
    if (candidates.empty()) break;
    // Longest first: splitting them first gives the better-shaped fans.
    std::sort(candidates.begin(), candidates.end());
    const size_t first_new = scope_vertices.size();
    for (size_t i = 0; i < candidates.size() && splits < max_splits; ++i) {
      // The fidelity splits, after the long ones, place their vertices on the reference: the
      // crossing guard checks them (split_placed_on_reference). A remesher that keeps its grid
      // has it already, unless this pass is expected to refine wholesale (run_iteration).
      if (i == long_ones && fidelity > 0) start_crossing_guard();
      splits += split_with_mirror(key_edge(candidates[i]), fidelity > 0);
    }
    // Only edges at the new vertices can still be too long: the others were not touched.
    split_recheck.clear();
    to_check = &split_recheck;
    for (size_t i = first_new; i < scope_vertices.size(); ++i)
      for (Halfedge h : mesh.halfedges(scope_vertices[i])) {
        Vertex w = mesh.to_vertex(h);
        if (scope[w] == kOutside) continue;
        // Each edge once: new-to-new edges from their lower-index end.
        bool w_new = w.idx >= scope_vertices[first_new].idx;
        if (!w_new || scope_vertices[i].idx < w.idx) split_recheck.push_back(mesh.edge(h));
      }
  }
  refining_wholesale = false;
  if (whole_mesh && splits >= max_splits) note_budget_reached();
  // Splits delete nothing; an added edge to a vertex outside the scope is not the scope's.
  const auto* hc = mesh.halfedge_connectivity_data();
  const std::uint8_t* sc = scope.vector().data();
  const mesh::Index n_edges = static_cast<mesh::Index>(mesh.edges_size());
  for (mesh::Index e = first_new_edge; e < n_edges; ++e)
    if (sc[hc[e << 1].to.idx] != kOutside && sc[hc[(e << 1) | 1u].to.idx] != kOutside) scope_edges.push_back(Edge(e));
  return splits;
}

// Whether collapsing h (from_vertex(h) into to_vertex(h)) is allowed by the scope, the
// feature rules and the mesh topology (link condition).
bool Remesher::Impl::collapse_topology_ok(Halfedge h) const {
  Halfedge o = mesh.opposite(h);
  Vertex v0 = mesh.from_vertex(h), v1 = mesh.to_vertex(h);
  if (scope[v0] != kActive || scope[v1] == kOutside) return false;
  if (vclass[v0] == kCorner && !is_line_kink(v0)) return false;
  if (anchored(v0)) return false;
  Edge e = mesh.edge(h);
  if (vclass[v0] != kFree) {
    // A feature vertex (or a kink of its line) may only slide along its own feature line.
    if (!is_feature(e)) return false;
  } else if (is_feature(e)) {
    return false;  // a free vertex cannot lie on a feature edge; be safe
  }
  // A removed triangle whose two other edges are both features would merge feature lines.
  if (!mesh.is_boundary(h) && is_feature(mesh.edge(mesh.next(h))) && is_feature(mesh.edge(mesh.prev(h))))
    return false;
  if (!mesh.is_boundary(o) && is_feature(mesh.edge(mesh.next(o))) && is_feature(mesh.edge(mesh.prev(o))))
    return false;
  return mesh.is_collapse_ok(h) && line_collapse_stays_near_reference(h);
}

// Geometric admissibility of merging the edge of h into one vertex at `target`: no edge grows
// beyond the split threshold (the collapse would be undone at once), and every surviving
// triangle around the moving end(s) keeps its orientation within 60 degrees and a non-zero area.
// The length test is the cheap one that fails most often, so it runs first over both rings.
bool Remesher::Impl::collapse_geometry_ok(Halfedge h, const Point& target, bool both_ends_move,
                                           bool check_lengths, double min_cos, bool check_reference_lines) const {
  Vertex v0 = mesh.from_vertex(h), v1 = mesh.to_vertex(h);
  Halfedge o = mesh.opposite(h);
  Vertex x = mesh.is_boundary(h) ? Vertex() : mesh.to_vertex(mesh.next(h));
  Vertex y = mesh.is_boundary(o) ? Vertex() : mesh.to_vertex(mesh.next(o));
  const double size = both_ends_move ? 0.5 * (sizing[v0] + sizing[v1]) : sizing[v1];
  auto lengths_ok = [&](Vertex centre, Vertex other) {
    for (Halfedge out : mesh.halfedges(centre)) {
      Vertex w = mesh.to_vertex(out);
      if (w == other || w == x || w == y) continue;
      double limit = kSplitFactor * std::min(size, sizing[w]);
      Vec3 d = mesh.position(w) - target;
      if (glm::dot(d, d) > limit * limit) return false;
    }
    return true;
  };
  auto normals_ok = [&](Vertex centre, Vertex other) {
    const Point& pc = mesh.position(centre);
    for (Halfedge out : mesh.halfedges(centre)) {
      if (mesh.is_boundary(out)) continue;
      Vertex w = mesh.to_vertex(out), w2 = mesh.to_vertex(mesh.next(out));
      if (w == other || w2 == other) continue;
      const Point& pw = mesh.position(w);
      const Point& pw2 = mesh.position(w2);
      Vec3 n_old = glm::cross(pw - pc, pw2 - pc);
      Vec3 n_new = glm::cross(pw - target, pw2 - target);
      double len_new = glm::length(n_new), len_old = glm::length(n_old);
      if (len_new <= 1e-14 * glm::dot(pw - target, pw - target)) return false;
      // No new triangle under a degree (it would be one as flat as those the input cleanup
      // removes): cgal/mask_cone.off's cone, cut open along a line, lost its apex fan down to one
      // triangle across the cut, flat, which no flip could mend (its long side is the border).
      if (min_angle_sin2(target, pw, pw2) < kDegenerateSin2 && min_angle_sin2(pc, pw, pw2) >= kDegenerateSin2)
        return false;
      // Old degenerate triangles have no orientation to keep.
      if (len_old > 0 && glm::dot(n_old, n_new) < min_cos * len_old * len_new) return false;
    }
    return true;
  };
  if (check_lengths && (!lengths_ok(v0, v1) || (both_ends_move && !lengths_ok(v1, v0)))) return false;
  // No new edge off the reference (fidelity.cpp), except for the sliver repair (no length test),
  // which allows a few tolerances itself (fix_bad_faces): held to one, it left the icosahedron at
  // epsilon 0.01 % a 3.4-degree triangle.
  return normals_ok(v0, v1) && (!both_ends_move || normals_ok(v1, v0)) &&
         (!check_reference_lines || collapse_stays_near_reference(h, target, both_ends_move)) &&
         (!check_lengths || collapse_keeps_fidelity(h, target, both_ends_move));
}

bool Remesher::Impl::collapse_allowed(Halfedge h) const {
  // Geometry before topology: the length test rejects most candidates of a converged mesh
  // and costs less than the link condition.
  return collapse_geometry_ok(h, mesh.position(mesh.to_vertex(h)), false) && collapse_topology_ok(h);
}

// The smallest angle among the triangles that collapsing h would reshape, as its squared sine
// (larger is better).
double Remesher::Impl::collapse_quality(Halfedge h) const {
  return fan_min_angle_sin2(mesh.from_vertex(h), mesh.position(mesh.to_vertex(h)), mesh.to_vertex(h));
}

double Remesher::Impl::fan_min_angle_sin2(Vertex v, const Point& at, Vertex skip) const {
  double worst = 1.0;
  for (Halfedge out : mesh.halfedges(v)) {
    if (mesh.is_boundary(out)) continue;
    Vertex w = mesh.to_vertex(out), w2 = mesh.to_vertex(mesh.next(out));
    if (w == skip || w2 == skip) continue;
    worst = std::min(worst, min_angle_sin2(at, mesh.position(w), mesh.position(w2)));
  }
  return worst;
}

bool Remesher::Impl::choose_collapse(Edge e, double ratio, Halfedge* h_out, bool* midpoint) const {
  Halfedge h0 = mesh.halfedge(e, 0), h1 = mesh.halfedge(e, 1);
  bool ok0 = collapse_allowed(h0), ok1 = collapse_allowed(h1);
  *midpoint = false;
  // The crossing test (the costly one) for the better of the two first, the other if it fails.
  const bool prefer1 = ok0 && ok1 && collapse_quality(h1) > collapse_quality(h0);
  for (const Halfedge h : {prefer1 ? h1 : h0, prefer1 ? h0 : h1})
    if ((h == h0 ? ok0 : ok1) && !collapse_crosses(h, mesh.position(mesh.to_vertex(h)), false)) {
      *h_out = h;
      return true;
    }
  // Neither end can take the other's place (typically on a thin or strongly curved part):
  // meeting in the middle often can, and leaves no sliver behind.
  // Only for edges far below the threshold: elsewhere endpoint collapses grade better.
  if (ratio > kMidpointCollapseRatio) return false;
  Vertex a = mesh.from_vertex(h0), b = mesh.to_vertex(h0);
  if (!movable(a) || !movable(b) || vclass[a] != kFree || vclass[b] != kFree) return false;
  if (anchored(a) || anchored(b)) return false;
  Point mid = 0.5 * (mesh.position(a) + mesh.position(b));
  if (!collapse_geometry_ok(h0, mid, true) || !collapse_topology_ok(h0) || collapse_crosses(h0, mid, true)) return false;
  *h_out = h0;
  *midpoint = true;
  return true;
}

void Remesher::Impl::apply_collapse(Halfedge h, bool midpoint) {
  if (midpoint) {
    Vertex a = mesh.from_vertex(h), b = mesh.to_vertex(h);
    sizing[b] = 0.5 * (sizing[a] + sizing[b]);
    mesh.position(b) = 0.5 * (mesh.position(a) + mesh.position(b));
  }
  // The mesh keeps the edges of prev(h) and next(opposite(h)); carry feature flags over
  // from the edges that disappear with the two triangles.
  Halfedge o = mesh.opposite(h);
  if (mask.is_valid()) {  // the survivor keeps the stronger mask of the two (neither is full)
    const Vertex a = mesh.from_vertex(h), b = mesh.to_vertex(h);
    mask[b] = std::max(mask[a], mask[b]);
  }
  if (!mesh.is_boundary(h)) feature[mesh.edge(mesh.prev(h))] |= feature[mesh.edge(mesh.next(h))];
  if (!mesh.is_boundary(o)) feature[mesh.edge(mesh.next(o))] |= feature[mesh.edge(mesh.prev(o))];
  if (deleted_faces_log) {  // the two triangles on the edge go with it
    if (!mesh.is_boundary(h)) deleted_faces_log->push_back(mesh.face(h));
    if (!mesh.is_boundary(o)) deleted_faces_log->push_back(mesh.face(o));
  }
  const Vertex survivor = mesh.to_vertex(h);
  mesh.collapse(h);
  note_fan_changed(survivor);
}

// Uses the scope's edges as the split pass left them (every edge of the scope); the flip passes
// after it reuse the list, since collapses and flips create no edges (a neck refinement's
// splits are left to the next iteration).
size_t Remesher::Impl::collapse_short_edges() {
  candidates.clear();
  for (Edge e : scope_edges) {
    double limit = kCollapseFactor * target_length(e);
    double l2 = squared_length(mesh, e);
    if (l2 < limit * limit) candidates.push_back(ascending_key(l2 / (limit * limit), e));
  }
  // Shortest first.
  std::sort(candidates.begin(), candidates.end());
  size_t collapses = 0;
  const size_t max_collapses = whole_mesh ? SIZE_MAX : scope_vertices.size() / kRegionCollapseShare + 1;
  for (const std::uint64_t c : candidates) {
    if (collapses >= max_collapses) break;
    const Edge e = key_edge(c);
    if (mesh.is_deleted(e)) continue;
    double limit = kCollapseFactor * target_length(e);
    if (squared_length(mesh, e) >= limit * limit) continue;  // neighbours changed it
    Halfedge h;
    bool midpoint = false;
    if (!choose_collapse(e, key_ratio(c), &h, &midpoint)) {
      // A short edge on the loop around a neck narrower than the sizing cannot collapse (link
      // condition): the sizing there is lowered to what the neck needs (neck.cpp).
      refine_neck_at(e);
      continue;
    }
    collapses += collapse_with_mirror(h, midpoint);
  }
  return collapses;
}

}  // namespace adasculpt::remesh
