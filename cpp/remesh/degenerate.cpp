// Zero-area input triangles, removed before the reference is built (the cleanup of CGAL's
// remove_degenerate_faces, done with the remesher's own operations).
//
// A zero-area triangle is a needle (an edge of length zero) or a cap (a corner on the opposite
// side, its "long edge"). Left in place, every split of one of its edges puts the new vertex on
// the same line and makes two more: degtri_sliding.off (two flat triangles joined by a strip of
// collinear ones) came out with 13,261 zero-area triangles of 18,444 at --uniform --length 0.5%.
//
// Both repairs leave the surface, as a set of points, exactly as it was:
// - a needle's zero-length edge collapses (its ends are at the same place);
// - a cap's long edge flips when the triangle across it has area: the two new triangles tile
//   that triangle, split at the cap's corner;
// - when the triangle across is a cap with the same long edge (a strip of collinear triangles),
//   the flip joins the two corners that lie on the edge: both new triangles are still on the line,
//   but with shorter long edges, so the strip is taken apart from its longest edges down until
//   each cap has a triangle with area across its long edge.
// The sum of the long edges of the zero-area triangles drops with every flip, and each collapse
// removes two triangles: the pass ends. What it cannot repair (features, masked or mirrored
// parts, boundaries) stays, and is not multiplied: the walk over the reference crosses the gap
// it leaves (reference.cpp), and the curvature there is not measured (geometry/curvature.cpp).
#include <algorithm>
#include <array>
#include <utility>

#include <glm/geometric.hpp>

#include "geometry/triangle.h"
#include "remesh/remesher_impl.h"

namespace adasculpt::remesh {

namespace {
// Squared shortest side over squared longest side below which a zero-area triangle is a needle:
// the ends of its shortest side coincide to about a millionth of the triangle (and, the triangle
// being collinear, its third corner is on their line), so collapsing that side moves nothing.
constexpr double kNeedleRatio2 = 1e-12;
// Whole passes over the faces: each does every repair it can find; later ones pick up the caps
// whose neighbour a flip of this pass made repairable. A strip of n collinear triangles takes
// about log2(n) passes; this is only the bound that makes the work finite whatever the input.
constexpr int kMaxPasses = 64;
// collapse_flat_across_features in uniform remeshing: how far from the reference its new edges may
// pass, as a share of the target length.
constexpr double kFlatCollapseLengthShare = 0.25;
}  // namespace

bool Remesher::Impl::is_zero_area(mesh::Face f) const {
  Vertex c[3];
  mesh.face_vertices(f, c);
  return geometry::is_degenerate_triangle(mesh.position(c[0]), mesh.position(c[1]), mesh.position(c[2]));
}

// The halfedge of f's longest side, and whether its shortest side has length zero.
Halfedge Remesher::Impl::longest_side(mesh::Face f, bool* needle, Halfedge* shortest) const {
  Halfedge h = mesh.halfedge(f), longest = h;
  *shortest = h;
  double max2 = -1, min2 = -1;
  for (int i = 0; i < 3; ++i, h = mesh.next(h)) {
    const Vec3 d = mesh.position(mesh.to_vertex(h)) - mesh.position(mesh.from_vertex(h));
    const double l2 = glm::dot(d, d);
    if (l2 > max2) max2 = l2, longest = h;
    if (min2 < 0 || l2 < min2) min2 = l2, *shortest = h;
  }
  *needle = min2 <= kNeedleRatio2 * max2;
  return longest;
}

bool Remesher::Impl::repair_flip_ok(Edge e) const {
  return !is_feature(e) && !mesh.is_boundary(e) && in_scope(e) && flip_spares_masked(e) && mesh.is_flip_ok(e);
}

// A cap whose long side is on the border, at an end of it with no other triangle (the border
// folds back on itself there, as at the apex of a cone cut open along a line): that end collapses
// onto the cap's corner along the short side, which removes the cap and nothing else. Left in
// place, the split passes cut the flat triangle's border edge again and again (a four-vertex
// input of one such cap and one triangle ended with 1,187 vertices, mean min angle 1.6 degrees).
// The end is a corner of the border, and no other repair may move a corner; here it carries no
// surface, so the feature classes do not apply.
bool Remesher::Impl::remove_border_ear(Halfedge long_side) {
  for (const Halfedge side : {mesh.opposite(mesh.prev(long_side)), mesh.next(long_side)}) {
    // side runs from an end of the long side to the cap's corner; the end has no other triangle
    // when both its edges are on the border.
    const Vertex end = mesh.from_vertex(side);
    if (scope[end] != kActive || masked(end)) continue;
    if (!mesh.is_boundary(mesh.edge(side)) || mesh.valence(end) != 2) continue;
    if (!mesh.is_collapse_ok(side)) continue;
    apply_collapse(side, false);
    return true;
  }
  return false;
}

size_t Remesher::Impl::remove_degenerate_faces() {
  if (mirror_axis >= 0) return 0;  // a repair on one side only would break the symmetry
  size_t repaired = 0;
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    size_t this_pass = 0;
    const size_t n_slots = mesh.faces_size();  // flips and collapses add no faces
    for (size_t k = 0; k < n_slots; ++k) {
      const mesh::Face f(static_cast<mesh::Index>(k));
      if (mesh.is_deleted(f) || !is_zero_area(f)) continue;
      bool needle;
      Halfedge shortest;
      const Halfedge long_side = longest_side(f, &needle, &shortest);
      if (needle) {
        for (Halfedge h : {shortest, mesh.opposite(shortest)})
          if (collapse_topology_ok(h) && collapse_geometry_ok(h, mesh.position(mesh.to_vertex(h)), false, false, 0.0)) {
            apply_collapse(h, false);
            ++this_pass;
            break;
          }
        continue;
      }
      const Edge e = mesh.edge(long_side);
      if (mesh.is_boundary(e) && remove_border_ear(long_side)) {
        ++this_pass;
        continue;
      }
      if (!repair_flip_ok(e)) continue;
      const mesh::Face across = mesh.face(mesh.opposite(long_side));
      bool across_needle;
      Halfedge unused;
      // Across: a triangle with area (the flip splits it at the cap's corner), or a cap on the
      // same line whose long edge is this one (the flip shortens both).
      if (is_zero_area(across) && (mesh.edge(longest_side(across, &across_needle, &unused)) != e || across_needle))
        continue;
      mesh.flip(e);
      ++this_pass;
    }
    repaired += this_pass;
    if (this_pass == 0) break;
  }
  return repaired;
}

// How far from the reference the repairs that merge or shorten feature lines may take the surface:
// the tolerance, or in uniform remeshing (no tolerance) a share of the target length; 0 where there
// is no current reference to measure against (regions, a stale reference).
double Remesher::Impl::feature_merge_tolerance() const {
  if (!has_reference || reference_stale || !whole_mesh) return 0;  // nothing to measure against
  return opt.adaptive ? fidelity_tolerance() : kFlatCollapseLengthShare * opt.target_length;
}

// polish()'s last repair of a triangle under a degree that the sliver repair (fix_bad_faces) could
// not remove because of the feature lines around it. On scans remeshed with --features 45, a flap
// of the input folded back onto its neighbour (dihedral angles near 180 degrees) makes two feature
// lines that run on top of each other; the remesher lays both on one line, and the strip of
// triangles between them has no area (cgal/pig.off at epsilon 1 %, features 45: three triangles of
// 0.00 degrees between two corners). Every other repair keeps feature lines apart and corners in
// place, so none applies there. This one collapses an edge of the triangle across those rules:
// - the shortest edge first, and a vertex that is not a corner first;
// - where the link condition holds, no triangle around it turns over or goes under a degree, and
//   the guard finds no crossing;
// - where the new edges stay within one tolerance of the reference (collapse_stays_within), not
//   the sliver repair's four: the triangle it removes is no sliver to trade against, and four took
//   cgal/3torus.off at epsilon 0.01 %, features 45, from a Hausdorff distance of 0.011 % to
//   0.040 %, twice the bound. Uniform remeshing has no tolerance (its bound is the target length):
//   there kFlatCollapseLengthShare of the length.
// At worst it merges two feature lines, which the output (a triangle mesh without feature marks)
// does not show; the survivor's class is counted again. Not repaired: a strip of many flat
// triangles in a row, where every collapse leaves a flat triangle that the guard refuses to create.
bool Remesher::Impl::collapse_flat_across_features(const Halfedge sides[3]) {
  if (mirror_axis >= 0) return false;  // a repair on one side only would break the symmetry
  const double tolerance = feature_merge_tolerance();
  if (!(tolerance > 0)) return false;
  std::array<std::pair<double, Halfedge>, 3> by_length;
  for (int i = 0; i < 3; ++i) {
    const Vec3 d = mesh.position(mesh.to_vertex(sides[i])) - mesh.position(mesh.from_vertex(sides[i]));
    by_length[i] = {glm::dot(d, d), sides[i]};
  }
  std::sort(by_length.begin(), by_length.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const bool move_corner : {false, true})
    for (const auto& side : by_length)
      for (const Halfedge h : {side.second, mesh.opposite(side.second)}) {
        const Vertex v0 = mesh.from_vertex(h), v1 = mesh.to_vertex(h);
        if ((vclass[v0] == kCorner) != move_corner) continue;
        if (scope[v0] != kActive || scope[v1] == kOutside || anchored(v0) || masked(v0)) continue;
        const Point target = mesh.position(v1);
        if (!mesh.is_collapse_ok(h) ||
            !collapse_geometry_ok(h, target, false, /*check_lengths=*/false, 0.5, /*check_reference_lines=*/false) ||
            collapse_crosses(h, target, false) || !collapse_stays_within(h, target, false, tolerance))
          continue;
        apply_collapse(h, false);
        int features = 0;
        for (const Halfedge out : mesh.halfedges(v1)) features += is_feature(mesh.edge(out));
        vclass[v1] = vertex_class(features);
        return true;
      }
  return false;
}

}  // namespace adasculpt::remesh
