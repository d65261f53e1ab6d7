// The last pass of a batch remesh for triangles still below the angle target: collapses that
// raise the smallest angle of the triangles they reshape.
//
// What reaches the end of the iterations below 20 degrees is mostly what neither a Delaunay flip
// (flip_for_angles) nor a move of a corner (place_sliver_vertices) can mend: a short edge between
// two vertices held on a border or feature line (cgal/blobby_3cc.off at epsilon 2 %: a border edge
// a third as long as its neighbours, 16.3 degrees), or a vertex crowded against a line whose edge
// may not flip. Removing one of the triangle's vertices can: each of the six endpoint collapses of
// its edges is tried, and the best is taken when the worst triangle it leaves around the moving
// vertex is better than the worst one there now (the triangle itself among them). The collapse
// keeps the guards of the regular pass (normals, one tolerance from the reference, no crossing,
// feature lines), but not the length limit: no split pass follows to undo it, and the fidelity
// check bounds what a longer edge costs the surface. blobby_3cc 16.3 -> 25.4 degrees, cgal/oblong
// at epsilon 0.5 %, features 45, 16.5 -> 24.3, cgal/man at 0.05 % 18.2 -> 20.3.
// Two collapses the feature rules forbid are allowed here, where the surface stays within the
// tolerance of the merges across feature lines (feature_merge_tolerance): a short line's end onto
// the line, and a line's detour around one triangle (below).
#include <algorithm>
#include <cmath>

#include "geometry/portable_math.h"
#include "geometry/triangle.h"
#include "remesh/remesher_impl.h"

namespace adasculpt::remesh {

namespace {
// Whole passes over the faces: a collapse can leave a neighbour the next pass improves. Each
// collapse removes a vertex, so the passes end anyway; this bounds them for any input.
constexpr int kMaxAnglePasses = 3;
}  // namespace

// The first exception to the feature rules here: the end of a feature line may collapse onto the
// line's next vertex, which shortens the line by that edge (a line of one edge goes away). In the
// iterations a line's end is a corner that never moves, so a short line (a crease of scan noise
// under --features, a few tolerances long) shrinks to one edge between its two ends, at its
// reference length however long the edges around it grow, and the triangles at it cannot be mended
// by any other operation: the shared face.off at epsilon 2 %, features 45, kept a 2.9-degree cap at
// a 0.3-long line with edges of 1.8 around it. The surface it leaves stays within the tolerance of
// the merges across feature lines (feature_merge_tolerance), checked by the caller with the other
// guards. Only an interior line's end (one feature edge, not a border), and only where neither
// removed triangle has feature edges on both its other sides (lines merged).
Halfedge Remesher::Impl::line_end_edge(Vertex v) const {
  Halfedge along;
  for (const Halfedge out : mesh.halfedges(v))
    if (is_feature(mesh.edge(out))) {
      if (along.is_valid()) return Halfedge();  // a second feature edge: no line's end
      along = out;
    }
  return along;
}

bool Remesher::Impl::line_end_collapse_ok(Halfedge h) const {
  if (mirror_axis >= 0) return false;  // a repair on one side only would break the symmetry
  const Halfedge o = mesh.opposite(h);
  const Vertex v0 = mesh.from_vertex(h), v1 = mesh.to_vertex(h);
  if (scope[v0] != kActive || scope[v1] == kOutside || anchored(v0) || masked(v0)) return false;
  if (line_end_edge(v0) != h || mesh.is_boundary(mesh.edge(h))) return false;  // v0's one feature edge
  if (is_feature(mesh.edge(mesh.next(h))) && is_feature(mesh.edge(mesh.prev(h)))) return false;
  if (is_feature(mesh.edge(mesh.next(o))) && is_feature(mesh.edge(mesh.prev(o)))) return false;
  return mesh.is_collapse_ok(h);
}

// The second exception: a feature line that makes a detour around one triangle. h's triangle has
// three feature edges, and h runs from a line's vertex whose two feature edges are two of them.
// Collapsing h takes the line onto the third side, a feature edge already, and removes the
// triangle, which no flip may touch (its sides are feature edges) and every other collapse of its
// corners would merge two lines. Interior edges only, and nothing else merges: the triangle across
// h may not have two feature edges besides.
bool Remesher::Impl::line_detour_collapse_ok(Halfedge h) const {
  if (mirror_axis >= 0 || mesh.is_boundary(h)) return false;
  const Halfedge o = mesh.opposite(h);
  if (mesh.is_boundary(o)) return false;
  const Vertex v0 = mesh.from_vertex(h), v1 = mesh.to_vertex(h);
  if (scope[v0] != kActive || scope[v1] == kOutside || anchored(v0) || masked(v0)) return false;
  if (vclass[v0] != kFeatureLine && !is_line_kink(v0)) return false;  // two feature edges, no more
  for (const Halfedge side : {h, mesh.next(h), mesh.prev(h)})
    if (!is_feature(mesh.edge(side)) || mesh.is_boundary(mesh.edge(side))) return false;
  if (is_feature(mesh.edge(mesh.next(o))) && is_feature(mesh.edge(mesh.prev(o)))) return false;
  return mesh.is_collapse_ok(h) && line_collapse_stays_near_reference(h);
}

size_t Remesher::Impl::collapse_for_angles(double angle_deg) {
  const double sin_limit = portable::sin(angle_deg * M_PI / 180.0);
  const double sin2_limit = sin_limit * sin_limit;
  const double merge_tolerance = feature_merge_tolerance();  // 0: no exceptions
  enum class Allowed { kNo, kRegular, kLineEnd, kDetour };
  auto allowed = [&](Halfedge h) {
    if (collapse_topology_ok(h)) return Allowed::kRegular;
    if (!(merge_tolerance > 0)) return Allowed::kNo;
    if (line_end_collapse_ok(h)) return Allowed::kLineEnd;
    return line_detour_collapse_ok(h) ? Allowed::kDetour : Allowed::kNo;
  };
  size_t collapsed = 0;
  for (int pass = 0; pass < kMaxAnglePasses; ++pass) {
    size_t this_pass = 0;
    const size_t n_slots = mesh.faces_size();  // collapses add no faces
    for (size_t k = 0; k < n_slots; ++k) {
      const mesh::Face f(static_cast<mesh::Index>(k));
      if (mesh.is_deleted(f)) continue;
      const Halfedge h0 = mesh.halfedge(f);
      const Halfedge hs[3] = {h0, mesh.next(h0), mesh.prev(h0)};
      const double now = min_angle_sin2(mesh.position(mesh.to_vertex(hs[0])), mesh.position(mesh.to_vertex(hs[1])),
                                        mesh.position(mesh.to_vertex(hs[2])));
      if (now >= sin2_limit) continue;
      Halfedge best;
      double best_after = 0;
      Allowed best_by = Allowed::kNo;
      // The six endpoint collapses of its sides, and for a corner that ends a feature line, the
      // collapse along the line (an edge of another triangle when the line leaves the corner
      // away from this one).
      Halfedge candidates[9];
      int n_candidates = 0;
      for (const Halfedge side : hs) {
        candidates[n_candidates++] = side;
        candidates[n_candidates++] = mesh.opposite(side);
        if (!(merge_tolerance > 0)) continue;
        const Halfedge along = line_end_edge(mesh.from_vertex(side));
        if (along.is_valid() && along != side && along != mesh.opposite(mesh.prev(side)))
          candidates[n_candidates++] = along;
      }
      for (int c = 0; c < n_candidates; ++c) {
        const Halfedge h = candidates[c];
        const double after = collapse_quality(h);
        // Better than the worst triangle the collapse reshapes or removes, and than the best so far.
        if (after <= best_after || after <= fan_min_angle_sin2(mesh.from_vertex(h), mesh.position(mesh.from_vertex(h)), Vertex())) continue;
        const Point& target = mesh.position(mesh.to_vertex(h));
        const Allowed by = allowed(h);
        if (by == Allowed::kNo || !collapse_geometry_ok(h, target, false, false)) continue;
        if (by == Allowed::kRegular ? !collapse_keeps_fidelity(h, target, false)
                                    : !collapse_stays_within(h, target, false, merge_tolerance))
          continue;
        if (collapse_crosses(h, target, false)) continue;
        best = h;
        best_after = after;
        best_by = by;
      }
      if (!best.is_valid()) continue;
      // After an exception the kept vertex has one feature edge less: a line's new end, free when
      // the line had that one edge, or a line's vertex when a line of one edge met another there.
      // After a detour the third corner too: its two sides merged into one.
      const Vertex kept = mesh.to_vertex(best), third = mesh.to_vertex(mesh.next(best));
      if (collapse_with_mirror(best, false) == 0) continue;
      ++this_pass;
      if (best_by != Allowed::kRegular) vclass[kept] = class_by_lines(kept);
      if (best_by == Allowed::kDetour) vclass[third] = class_by_lines(third);
    }
    collapsed += this_pass;
    if (!this_pass) break;
  }
  return collapsed;
}

}  // namespace adasculpt::remesh
