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

size_t Remesher::Impl::collapse_for_angles(double angle_deg) {
  const double sin_limit = portable::sin(angle_deg * M_PI / 180.0);
  const double sin2_limit = sin_limit * sin_limit;
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
      for (const Halfedge side : hs)
        for (const Halfedge h : {side, mesh.opposite(side)}) {
          const double after = collapse_quality(h);
          // Better than the worst triangle the collapse reshapes or removes, and than the best so far.
          if (after <= best_after || after <= fan_min_angle_sin2(mesh.from_vertex(h), mesh.position(mesh.from_vertex(h)), Vertex())) continue;
          const Point& target = mesh.position(mesh.to_vertex(h));
          if (!collapse_topology_ok(h) || !collapse_geometry_ok(h, target, false, false)) continue;
          if (!collapse_keeps_fidelity(h, target, false)) continue;
          if (collapse_crosses(h, target, false)) continue;
          best = h;
          best_after = after;
        }
      if (best.is_valid() && collapse_with_mirror(best, false) != 0) ++this_pass;
    }
    collapsed += this_pass;
    if (!this_pass) break;
  }
  return collapsed;
}

}  // namespace adasculpt::remesh
