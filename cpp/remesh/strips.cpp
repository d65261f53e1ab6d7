// Strips between creases: where two sharp edges (creases, feature lines or the border) run side
// by side closer than the sizing, triangles as long as the sizing cannot lie between them. Each
// row of triangles across the strip has one short side (the strip's width) and two long ones:
// slivers that no flip or collapse can mend, because every vertex is held on one of the two
// creases. cgal/rotor.off has a flat ring 0.02 wide between two 90-degree creases; at epsilon
// 0.5 % its edges were 0.07 long and its triangles 16 degrees. The sizing at such a strip is
// clamped to twice its width, so the strip gets triangles that fit it (where that is not below
// min_length, the user's floor).
//
// The strips are found on the reference's own triangles: a triangle with a crease edge whose
// opposite corner lies on another crease running alongside (within kParallelDeg of parallel)
// spans the strip, and its height over the crease edge is the strip's width there. A coarse CAD
// input, the case where this matters, meshes its strips that way: finer inputs measure their
// curvature across the strip already. Two lines that meet at a corner are no strip: the angle
// between them bounds the triangles there whatever the sizing.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "remesh/remesher_impl.h"

namespace adasculpt::remesh {

namespace {
// An interior edge is a crease when its faces turn by more than this.
constexpr double kStripCreaseDeg = 30.0;
// The opposite corner's crease runs alongside the edge when their directions are this close.
constexpr double kParallelDeg = 30.0;
// The sizing at a strip, in strip widths: with edges up to 4/3 of the sizing along it, a triangle
// across is one width high on a side of at most 2.7 widths, no angle under 20 degrees even with
// its apex over an end of that side (37 degrees over its middle). 1.2 widths (51 degrees) cost
// cgal/rotor.off 1.5 times the vertices of 2.
constexpr double kStripWidths = 2.0;
// A strip triangle's crease side is at least this many times the strip's width.
constexpr double kNeedleLength = 3.0;
// The sizing at both corners of a short border edge, in lengths of that edge: with sides up to
// 4/3 of it, the triangle on the edge keeps an angle over 20 degrees at its apex.
constexpr double kShortEdgeLengths = 2.0;
// ... applied where the input's edges at both corners are at most this many times that sizing.
constexpr double kLocalSpread = 8.0;
}  // namespace

void Remesher::Impl::clamp_sizing_to_strips() {
  if (!has_reference) return;
  const double crease_cos = std::cos(kStripCreaseDeg * M_PI / 180.0);
  const double parallel_cos = std::cos(kParallelDeg * M_PI / 180.0);
  // coverage_limit() as it will be once the reference is built (it is 0 while it is stale).
  const double limit = kCoverageLimit * std::max(opt.epsilon, kToleranceMinLengths * opt.min_length);
  // Whether the remesh must follow the crease at h across a strip `width` wide: feature lines and
  // the border always; a crease of features off only where a chord across the strip would cut it
  // by more than the coverage check allows (coverage.cpp: its reach times the sine of half its
  // turn). Elsewhere the mesh may cut the strip off within the tolerance, as it did before, and
  // refining it would only add vertices (a stepped cylinder at epsilon 0.5 %: 3.5 times as many).
  auto followed = [&](Halfedge h, double width) {
    if (mesh.is_boundary(SurfaceMesh::edge(h)) || is_feature(SurfaceMesh::edge(h))) return true;
    const Vec3 n0 = geometry::face_normal(mesh, mesh.face(h));
    const Vec3 n1 = geometry::face_normal(mesh, mesh.face(mesh.opposite(h)));
    if (glm::dot(n0, n0) == 0.0 || glm::dot(n1, n1) == 0.0) return false;  // degenerate: no angle
    const double c = glm::dot(n0, n1);
    const double sin_half = std::sqrt(std::max(0.0, 0.5 * (1 - c)));
    return c < crease_cos && width * sin_half > limit;
  };
  for (mesh::Face f : mesh.faces()) {
    for (Halfedge h : mesh.halfedges(f)) {
      const Vertex a = mesh.from_vertex(h), b = mesh.to_vertex(h), x = mesh.to_vertex(mesh.next(h));
      const Vec3 along = mesh.position(b) - mesh.position(a);
      const double length = glm::length(along);
      if (!(length > 0)) continue;
      const double width = glm::length(glm::cross(along, mesh.position(x) - mesh.position(a))) / length;
      // A strip's triangle is a needle along it, not one of sides alike (a scan's noisy sharp
      // edges, with features on).
      if (!(length >= kNeedleLength * width)) continue;
      // A strip narrower than the min length, the user's floor, cannot get triangles that fit it:
      // sizing it down to the floor only multiplied the vertices around it (cgal/mpi.off, a step
      // 0.003 % of the diagonal high, at epsilon 2 %, features 45: 899 -> 9,703, the slivers kept).
      const double cap = kStripWidths * width;
      if (!(cap >= opt.min_length)) continue;
      if (!(cap < std::max(sizing[a], std::max(sizing[b], sizing[x])))) continue;  // nothing to clamp
      // Not at corners: where a feature line ends or meets others, the strip is a sector (bounded
      // by the lines' own angle) or, on a scan with features on, noise whose lines break every few
      // edges; clamped there, the vertices grew 2-2.3 times for the same min angle (at epsilon 2 %,
      // features 45: cgal/elk 1,469 -> 3,306, cgal/ChineseDragon-10kv 3,175 -> 6,572).
      if (vclass[a] == kCorner || vclass[b] == kCorner || vclass[x] == kCorner) continue;
      if (!followed(h, width)) continue;
      // Not where the triangle's other sides are creases too: x is then on a line that leaves a or
      // b, two lines meeting at a corner (their sector bounds the angles there anyway).
      if (followed(mesh.next(h), width) || followed(mesh.prev(h), width)) continue;
      // Does a followed crease at x (other than this triangle's own edges) run alongside a -> b?
      bool alongside = false;
      for (Halfedge out : mesh.halfedges(x)) {
        const Vertex y = mesh.to_vertex(out);
        if (y == a || y == b) continue;
        const Vec3 d = mesh.position(y) - mesh.position(x);
        const double dl = glm::length(d);
        if (dl > 0 && std::abs(glm::dot(d, along)) >= parallel_cos * dl * length && followed(out, width)) {
          alongside = true;
          break;
        }
      }
      if (!alongside) continue;
      for (Vertex v : {a, b, x}) sizing[v] = std::min(sizing[v], cap);
    }
  }
}

// Short border edges between two corners: where the border of a hole turns sharply at both ends
// of an edge much shorter than the sizing (a scan's ragged hole), the triangle on that edge has it
// as its base and two sides as long as the sizing: cgal/lion at epsilon 2 % had 4.6-degree ones,
// cgal/elephant-with-holes 12.6 degrees at 5 %. Both corners stay (they are the border's), so
// the sizing there is clamped to kShortEdgeLengths times the edge, and the triangles on it get
// sides that fit it. Only where the input's own edges at both corners are at most kLocalSpread
// times that: the clamp is set at the corners and interpolated over the input's triangles, which
// on a coarse input fills whole faces with the small sizing. Feature lines are left out: clamped
// at their corners too, and without the local condition, gen/thin_plate at features 45 (1 x 1
// faces around a 0.002 rim) went from 0.05 s past the sweep's 10 s cap, and scans at features 45,
// whose corners come every few edges, got 2-3.5 times the vertices (cgal/bull at epsilon 2 %:
// 3,460 -> 12,280).
void Remesher::Impl::clamp_sizing_to_short_lines() {
  auto local = [&](Vertex v, double cap) {
    for (Halfedge h : mesh.halfedges(v))
      if (glm::length(mesh.position(mesh.to_vertex(h)) - mesh.position(v)) > kLocalSpread * cap) return false;
    return true;
  };
  for (Edge e : mesh.edges()) {
    if (!mesh.is_boundary(e)) continue;
    const Vertex a = mesh.vertex(e, 0), b = mesh.vertex(e, 1);
    if (vclass[a] != kCorner || vclass[b] != kCorner) continue;
    const double cap = kShortEdgeLengths * glm::length(mesh.position(a) - mesh.position(b));
    // Nothing to clamp, or a floor the user set above it.
    if (!(cap >= opt.min_length) || !(cap < std::max(sizing[a], sizing[b]))) continue;
    if (!local(a, cap) || !local(b, cap)) continue;
    sizing[a] = std::min(sizing[a], cap);
    sizing[b] = std::min(sizing[b], cap);
  }
}

}  // namespace adasculpt::remesh
