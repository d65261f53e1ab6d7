// Connectivity and position passes of a remeshing iteration: valence-driven edge flips and
// the paper's area-and-sizing weighted tangential relaxation (equation 6), then projection.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "geometry/normal_tensor.h"
#include "geometry/portable_math.h"
#include "geometry/triangle.h"
#include "remesh/remesher_impl.h"

namespace adasculpt::remesh {

namespace {
using mesh::Index;
// A fan whose area-weighted normal is shorter than this share of its area is folded (the normals
// of a 90 degree crease give cos 45 = 0.71). When its normals also lie along one axis
// (NormalTensor: the middle eigenvalue below kSheetAxisShare of the largest), it is the rim of a
// part thinner than its edges, two sheets facing opposite ways: its tangent plane is noise, and
// equation 6 moved such a vertex into the part, where the projection put it on a sheet. The
// vertex stays where it is. Measured on gen/thin_plate (a 1 x 1 plate 0.002 thick, features off):
// each iteration ate further into the rim, at epsilon 2 % 7.6 % of the diagonal deep after five
// (bound 4 %); with this 0.14 %. A folded fan whose normals turn about an axis (a crease)
// or spread every way (a tip, a crumpled scan) relaxes as any other: moved along the crease
// instead, the dragon's smallest angle at the defaults fell from 25 to 22 degrees.
constexpr double kFoldedNormalShare = 0.7;
constexpr double kSheetAxisShare = 0.2;
}  // namespace

// A flip must not fold the surface: both new triangles keep the orientation of the quad and
// stay non-degenerate, and the quad must be nearly flat (otherwise the flip changes shape).
bool Remesher::Impl::flip_geometry_ok(Edge e, bool require_flat) const {
  Halfedge h = mesh.halfedge(e, 0), o = mesh.halfedge(e, 1);
  const Point& a = mesh.position(mesh.to_vertex(o));
  const Point& b = mesh.position(mesh.to_vertex(h));
  const Point& c = mesh.position(mesh.to_vertex(mesh.next(h)));
  const Point& d = mesh.position(mesh.to_vertex(mesh.next(o)));
  Vec3 n1 = glm::cross(b - a, c - a);  // (a, b, c)
  Vec3 n2 = glm::cross(a - b, d - b);  // (b, a, d)
  Vec3 m1 = glm::cross(d - a, c - a);  // (a, d, c)
  Vec3 m2 = glm::cross(b - d, c - d);  // (d, b, c)
  double l1 = glm::length(n1), l2 = glm::length(n2), k1 = glm::length(m1), k2 = glm::length(m2);
  double scale = glm::dot(c - d, c - d);
  if (k1 <= 1e-12 * scale || k2 <= 1e-12 * scale) return false;
  Vec3 avg = n1 + n2;
  if (glm::dot(m1, avg) <= 0 || glm::dot(m2, avg) <= 0) return false;
  if (!require_flat) return !crossing_guard.flip_crosses(mesh, e);
  // The new triangles must agree with each other at least as well as the old ones did.
  double old_cos = (l1 > 0 && l2 > 0) ? glm::dot(n1, n2) / (l1 * l2) : -1.0;
  double new_cos = glm::dot(m1, m2) / (k1 * k2);
  return new_cos >= std::min(old_cos, 0.9) - 1e-12 && new_cos > 0.5 && !crossing_guard.flip_crosses(mesh, e);
}

// SurfaceMesh::is_flip_ok with the valences this pass keeps up to date, and the search for
// an existing edge c-d around whichever end has fewer edges: a vertex of huge valence (a stray
// point far away gathers thousands of needles) must not make every flip test walk its fan.
bool Remesher::Impl::flip_topology_ok(Edge e) const {
  if (mesh.is_boundary(e)) return false;
  Halfedge h = mesh.halfedge(e, 0), o = mesh.halfedge(e, 1);
  Vertex a = mesh.to_vertex(o), b = mesh.to_vertex(h);
  Vertex c = mesh.to_vertex(mesh.next(h)), d = mesh.to_vertex(mesh.next(o));
  if (c == d) return false;
  if (!mesh.is_boundary(a) && valence[a.idx] <= 3) return false;
  if (!mesh.is_boundary(b) && valence[b.idx] <= 3) return false;
  Vertex from = valence[c.idx] <= valence[d.idx] ? c : d, to = from == c ? d : c;
  for (Halfedge g : mesh.halfedges(from))
    if (mesh.to_vertex(g) == to) return false;
  return true;
}

void Remesher::Impl::flip_counting(Edge e) {
  const auto* hc = mesh.halfedge_connectivity_data();
  const auto& h = hc[e.idx << 1];
  const auto& o = hc[(e.idx << 1) | 1u];
  const Index corner[4] = {o.to.idx, h.to.idx, hc[h.next.idx].to.idx, hc[o.next.idx].to.idx};  // a, b lose; c, d gain
  mesh.flip(e);
  crossing_guard.flipped(mesh, e);
  for (int i = 0; i < 4; ++i) {
    const int change = i < 2 ? -1 : 1;
    valence[corner[i]] += change;
    valence_excess[corner[i]] += change;
  }
}

// Uses scope_edges as collapse_short_edges left them (collapses delete edges but create none).
// The loops read the mesh's flat arrays (flips add no elements, so the pointers stay valid): on
// a converged mesh almost every edge is rejected by the valence test, which must stay cheap.
size_t Remesher::Impl::flip_edges() {
  mesh::resize_scratch(valence, mesh.vertices_size());
  mesh::resize_scratch(valence_excess, mesh.vertices_size());
  const auto* hc = mesh.halfedge_connectivity_data();
  const Halfedge* vh = mesh.vertex_halfedge_data();
  const std::uint8_t* vdel = mesh.vertex_deleted_data();
  const std::uint8_t* edel = mesh.edge_deleted_data();
  const std::uint8_t* feat = feature.vector().data();
  const std::uint8_t* sc = scope.vector().data();
  int* val = valence.data();
  int* excess = valence_excess.data();
  for (Vertex v : scope_vertices) {
    if (vdel[v.idx]) continue;
    // SurfaceMesh::valence, and its excess over the target: 4 on the boundary, 6 inside (flips
    // keep every vertex's boundary status).
    const Halfedge start = vh[v.idx];
    int n = 0;
    for_each_outgoing(hc, vh, v, [&](Halfedge) { ++n; });
    val[v.idx] = n;
    excess[v.idx] = n - (!start.is_valid() || !hc[start.idx].face.is_valid() ? 4 : 6);
  }
  size_t flips = 0;
  for (Edge e : scope_edges) {
    if (edel[e.idx] || feat[e.idx]) continue;
    const auto& ch = hc[e.idx << 1];
    const auto& co = hc[(e.idx << 1) | 1u];
    if (!ch.face.is_valid() || !co.face.is_valid()) continue;  // boundary edge
    const Index a = co.to.idx, b = ch.to.idx, c = hc[ch.next.idx].to.idx, d = hc[co.next.idx].to.idx;
    // All four corners must be in the iteration's scope; held border vertices may gain or
    // lose an edge, outside vertices may not.
    if (sc[c] == kOutside || sc[d] == kOutside) continue;
    // The flip lowers the sum of squared excesses, sum (x_i - t_i)^2 over the four corners, when
    // a and b lose an edge and c and d gain one: the difference after - before is
    // 4 + 2 (xc + xd - xa - xb), exactly, in integers.
    if (excess[a] + excess[b] - excess[c] - excess[d] <= 2) continue;
    if (!flip_topology_ok(e) || !flip_geometry_ok(e, true)) continue;
    if (!flip_keeps_fidelity(e)) continue;  // no edge off the reference (fidelity.cpp)
    const Edge image = flip_partner(e);
    if (!image.is_valid() || (image != e && !flip_topology_ok(image))) continue;
    flip_counting(e);
    if (image != e) flip_counting(image);
    flips += image != e ? 2 : 1;
  }
  return flips;
}

// Flips that raise the smaller of the two triangles' minimum angles, for pairs containing a
// poor triangle: the valence flips leave a few of these where the sizing changes quickly.
// Uses scope_edges as the flip pass left them (flips create no edges).
size_t Remesher::Impl::flip_for_angles(double poor_angle) {
  const double poor_sin2 = portable::sin(poor_angle) * portable::sin(poor_angle);
  // Each face's smallest-angle measure once, not once per edge: most edges of a good mesh
  // are rejected by these two lookups alone.
  mesh::resize_scratch(face_quality, mesh.faces_size());
  const auto* hc = mesh.halfedge_connectivity_data();
  const Halfedge* fh = mesh.face_halfedge_data();
  const std::uint8_t* edel = mesh.edge_deleted_data();
  const std::uint8_t* feat = feature.vector().data();
  const std::uint8_t* sc = scope.vector().data();
  const Point* pos = mesh.positions().data();
  double* fq = face_quality.data();
  // Inlined by hand: clang left it a call in the wasm build (7 % of a smooth stamp).
  auto quality_of = [&](Index f) __attribute__((always_inline)) {
    const Halfedge h0 = fh[f], h1 = hc[h0.idx].next, h2 = hc[h1.idx].next;
    return min_angle_sin2(pos[hc[h0.idx].to.idx], pos[hc[h1.idx].to.idx], pos[hc[h2.idx].to.idx]);
  };
  if (whole_mesh) {
    const std::uint8_t* fdel = mesh.face_deleted_data();
    const Index n_faces = static_cast<Index>(mesh.faces_size());
    for (Index f = 0; f < n_faces; ++f)
      if (!fdel[f]) fq[f] = quality_of(f);
  } else {
    // Each face once, though up to three of its edges are in scope.
    mesh::resize_scratch(face_seen, mesh.faces_size(), 0u);
    if (++face_run == 0) {
      std::fill(face_seen.begin(), face_seen.end(), 0);
      face_run = 1;
    }
    std::uint32_t* seen = face_seen.data();
    for (Edge e : scope_edges)
      for (unsigned i = 0; i < 2 && !edel[e.idx]; ++i) {
        mesh::Face f = hc[(e.idx << 1) | i].face;
        if (f.is_valid() && seen[f.idx] != face_run) {
          seen[f.idx] = face_run;
          fq[f.idx] = quality_of(f.idx);
        }
      }
  }
  size_t flips = 0;
  for (Edge e : scope_edges) {
    if (edel[e.idx] || feat[e.idx]) continue;
    const auto& ch = hc[e.idx << 1];
    const auto& co = hc[(e.idx << 1) | 1u];
    const mesh::Face f1 = ch.face, f2 = co.face;
    if (!f1.is_valid() || !f2.is_valid()) continue;  // boundary edge
    double before = std::min(fq[f1.idx], fq[f2.idx]);
    if (before >= poor_sin2) continue;
    const Index va = co.to.idx, vb = ch.to.idx, vc = hc[ch.next.idx].to.idx, vd = hc[co.next.idx].to.idx;
    if (sc[vc] == kOutside || sc[vd] == kOutside) continue;
    const Point &a = pos[va], &b = pos[vb], &c = pos[vc], &d = pos[vd];
    // Delaunay test: the angles gamma, delta opposite the edge sum to more than pi, i.e.
    // sin(gamma + delta) < 0 (both lie in (0, pi)); no trigonometric calls needed.
    Vec3 ca = a - c, cb = b - c, da = a - d, db = b - d;
    double sin_sum = glm::length(glm::cross(ca, cb)) * glm::dot(da, db) + glm::dot(ca, cb) * glm::length(glm::cross(da, db));
    if (sin_sum >= 0) continue;
    double q1 = min_angle_sin2(a, d, c), q2 = min_angle_sin2(d, b, c);
    if (std::min(q1, q2) <= before) continue;
    if (!flip_topology_ok(e) || !flip_geometry_ok(e, true)) continue;
    if (!flip_keeps_fidelity(e)) continue;  // (fidelity.cpp)
    const Edge image = flip_partner(e);
    if (!image.is_valid() || (image != e && !flip_topology_ok(image))) continue;
    flip_counting(e);
    // flip() keeps the face slots: f1 is now (a, d, c), f2 is (d, b, c).
    fq[f1.idx] = q1;
    fq[f2.idx] = q2;
    ++flips;
    if (image != e) {
      flip_counting(image);
      for (unsigned i = 0; i < 2; ++i) {
        const Index g = hc[(image.idx << 1) | i].face.idx;
        fq[g] = quality_of(g);
      }
      ++flips;
    }
  }
  return flips;
}

void Remesher::Impl::relax_vertices() {
  new_positions.resize(scope_vertices.size());
  const bool keep_shape = keep_fan_shapes;
  if (keep_shape) fan_shapes.assign(scope_vertices.size(), FanShape{Vec3(0.0), false});
  mesh::resize_scratch(relax_faces, mesh.faces_size());
  mesh::resize_scratch(face_seen, mesh.faces_size(), 0u);
  if (++face_run == 0) {
    std::fill(face_seen.begin(), face_seen.end(), 0);
    face_run = 1;
  }
  std::uint32_t* seen = face_seen.data();
  const Halfedge* fh = mesh.face_halfedge_data();
  // Flat arrays: nothing is added to the mesh until the positions are written back.
  const auto* hc = mesh.halfedge_connectivity_data();
  const Halfedge* vh = mesh.vertex_halfedge_data();
  const std::uint8_t* vdel = mesh.vertex_deleted_data();
  const std::uint8_t* sc = scope.vector().data();
  const std::uint8_t* vcl = vclass.vector().data();
  const double* siz = sizing.vector().data();
  const Point* pos = mesh.positions().data();
  // In a region call, the faces with an active corner are listed as they are first met: the
  // sliver pass after this one checks exactly those (fix_bad_faces), and walked every fan of the
  // region again to find them.
  faces_scratch.clear();
  const bool list_faces = !whole_mesh;
  // Equation 6's terms of face f: computed once per call, from its own corners, and shared by
  // its corners (they were computed once per corner: a fifth of a sculpting frame's instructions).
  auto face_terms = [&](mesh::Face f) __attribute__((always_inline)) -> const RelaxFace& {
    RelaxFace& t = relax_faces[f.idx];
    if (seen[f.idx] != face_run) {
      seen[f.idx] = face_run;
      if (list_faces) faces_scratch.push_back(f);
      const auto& c0 = hc[fh[f.idx].idx];
      const Index a = c0.to.idx, b = hc[c0.next.idx].to.idx, d = hc[c0.prev.idx].to.idx;
      t.normal = glm::cross(pos[b] - pos[a], pos[d] - pos[a]);
      t.area2 = glm::length(t.normal);
      t.weight = 0.5 * t.area2 * ((siz[a] + siz[b] + siz[d]) / 3.0);
      t.weighted_centre = t.weight * (pos[a] + pos[b] + pos[d]) / 3.0;
    }
    return t;
  };
  for (size_t i = 0; i < scope_vertices.size(); ++i) {
    Vertex v = scope_vertices[i];
    if (vdel[v.idx]) continue;
    const Point p = pos[v.idx];
    new_positions[i] = p;
    if (sc[v.idx] != kActive) continue;  // held
    if (vcl[v.idx] != kFree) {
      // Not moved by equation 6 (corners not at all): their faces are listed all the same.
      if (list_faces)
        for_each_outgoing(hc, vh, v, [&](Halfedge h) {
          if (hc[h.idx].face.is_valid()) face_terms(hc[h.idx].face);
        });
      if (vcl[v.idx] == kCorner) continue;
      // Along the feature line: the two feature edges' midpoints weighted by length x sizing.
      Vertex ends[2];
      int n = 0;
      for (Halfedge h : mesh.halfedges(v))
        if (is_feature(mesh.edge(h)) && n < 2) ends[n++] = mesh.to_vertex(h);
      if (n != 2) continue;
      const Point& pa = mesh.position(ends[0]);
      const Point& pb = mesh.position(ends[1]);
      double wa = glm::length(pa - p) * 0.5 * (sizing[v] + sizing[ends[0]]);
      double wb = glm::length(pb - p) * 0.5 * (sizing[v] + sizing[ends[1]]);
      if (wa + wb <= 0) continue;
      Point c = (wa * 0.5 * (p + pa) + wb * 0.5 * (p + pb)) / (wa + wb);
      Vec3 t = pb - pa;
      double tl = glm::dot(t, t);
      if (tl <= 0) continue;
      new_positions[i] = p + t * (glm::dot(c - p, t) / tl);
      continue;
    }
    // Equation 6: triangle barycentres weighted by area x sizing at the barycentre.
    Vec3 normal(0.0);
    Point c(0.0);
    double weight = 0, area2 = 0;
    FanCreaseTest crease;
    for_each_outgoing(hc, vh, v, [&](Halfedge h) {
      const mesh::Face f = hc[h.idx].face;
      if (!f.is_valid()) {
        if (keep_shape) crease.gap();
        return;
      }
      const RelaxFace& t = face_terms(f);
      normal += t.normal;
      c += t.weighted_centre;
      weight += t.weight;
      area2 += t.area2;
      if (keep_shape) crease.add(t.normal);
    });
    if (keep_shape) fan_shapes[i] = {normal, crease.creased()};  // for the projection (safety.cpp)
    double nl = glm::length(normal);
    if (weight <= 0 || nl <= 0) continue;
    const Vec3 u = c / weight - p;
    if (nl < kFoldedNormalShare * area2) {
      geometry::NormalTensor normals;
      for_each_outgoing(hc, vh, v, [&](Halfedge h) {
        if (hc[h.idx].face.is_valid()) normals.add(relax_faces[hc[h.idx].face.idx].normal);
      });
      if (normals.along_one_axis(kSheetAxisShare)) continue;
    }
    normal /= nl;
    new_positions[i] = p + (u - normal * glm::dot(normal, u));
  }
  active_faces_listed = list_faces;
  Point* out = mesh.positions().data();
  for (size_t i = 0; i < scope_vertices.size(); ++i) {
    const Index v = scope_vertices[i].idx;
    if (!vdel[v] && sc[v] == kActive && vcl[v] != kCorner) out[v] = new_positions[i];  // movable(v)
  }
  if (mirror_axis >= 0) symmetrize_positions();
}

// Removes triangles with an angle below `angle_deg` (zero-area and needle triangles of the
// input, and the rare sliver the regular passes could not avoid): collapse their shortest edge
// when it is short, otherwise flip their longest edge (a "cap" has no short edge); a cap on a
// border or feature line, whose longest edge may not flip, collapses one of its other two edges.
//
// The collapse and the flip may take the surface two tolerances from the reference (the Hausdorff
// target, kSliverRepairToleranceTimes), not farther (the regular passes keep one; held to one
// here, the sliver stays more often: gen/thin_plate at epsilon 0.05 % got 4 % more vertices and a
// worse rim). Without a bound:
// - the collapses joined far sides of gen/sliver_cylinder with chords through its inside: the
//   vertex budget cuts the first split pass of its needle strips short, and the repair then took
//   7.8k vertices down to 740, the chords' midpoints 0.05 inside, out of the projection's reach in
//   the later iterations (Hausdorff 13 x the tolerance at epsilon 0.05 %; now 0.78 x);
// - the flips made edges 20 tolerances off across cgal/3torus's 16-degree creases (epsilon 0.01 %,
//   features 45); the next split pass put vertices at their midpoints, and the crossing guard
//   sent the projected ones back there (Hausdorff 0.22 % of the diagonal; now 0.008 %).
size_t Remesher::Impl::fix_bad_faces(double angle_deg) {
  const double sin_limit = portable::sin(angle_deg * M_PI / 180.0);
  const double sin2_limit = sin_limit * sin_limit;
  size_t fixed = 0;
  // The faces relax_vertices listed, when it ran just before (the first pass; the passes after a
  // fix gather them again).
  bool listed = active_faces_listed && !whole_mesh;
  active_faces_listed = false;
  for (int pass = 0; pass < 3; ++pass) {
    size_t fixed_this_pass = 0;
    if (!listed) faces_scratch.clear();
    // Flat arrays: collapses and flips add no elements, so the pointers stay valid.
    const auto* hc = mesh.halfedge_connectivity_data();
    const Halfedge* fh = mesh.face_halfedge_data();
    const std::uint8_t* fdel = mesh.face_deleted_data();
    const Point* pos = mesh.positions().data();
    if (whole_mesh || listed) {
      // Whole mesh: every face slot in order, below: collapses and flips add no faces, and the
      // deleted check at each visit skips what the snapshot of live faces would have skipped.
      listed = false;
    } else {
      // Each face once: from its first active corner in halfedge order.
      const Halfedge* vh = mesh.vertex_halfedge_data();
      const std::uint8_t* vdel = mesh.vertex_deleted_data();
      const std::uint8_t* sc = scope.vector().data();
      for (Vertex v : scope_vertices) {
        if (vdel[v.idx] || sc[v.idx] != kActive) continue;
        for_each_outgoing(hc, vh, v, [&](Halfedge h) {
          const auto& ch = hc[h.idx];
          if (!ch.face.is_valid()) return;
          const mesh::Index prev_corner = hc[ch.next.idx].to.idx;  // the corner before v
          const mesh::Index next_corner = ch.to.idx;
          const bool earlier = (sc[prev_corner] == kActive && prev_corner < v.idx) ||
                               (sc[next_corner] == kActive && next_corner < v.idx);
          if (!earlier) faces_scratch.push_back(ch.face);
        });
      }
    }
    const size_t n_visits = whole_mesh ? mesh.faces_size() : faces_scratch.size();
    for (size_t k = 0; k < n_visits; ++k) {
      const mesh::Face f = whole_mesh ? mesh::Face(static_cast<Index>(k)) : faces_scratch[k];
      if (fdel[f.idx]) continue;
      const Halfedge h0 = fh[f.idx];
      Halfedge hs[3] = {h0, hc[h0.idx].next, hc[h0.idx].prev};
      const Point &q0 = pos[hc[hs[0].idx].to.idx], &q1 = pos[hc[hs[1].idx].to.idx], &q2 = pos[hc[hs[2].idx].to.idx];
      if (min_angle_sin2(q0, q1, q2) >= sin2_limit) continue;
      const Point p[3] = {q0, q1, q2};
      // Edge lengths: hs[i] runs from p[(i+2)%3] to p[i].
      double len[3];
      for (int i = 0; i < 3; ++i) len[i] = glm::length(p[i] - p[(i + 2) % 3]);
      int shortest = int(std::min_element(len, len + 3) - len);
      int longest = int(std::max_element(len, len + 3) - len);
      // A sliver's neighbours may end up a little beyond the split threshold, and its fan may turn
      // by up to 90 degrees (folded input such as self-intersections): accepted here, the next
      // passes even that out, while the sliver would stay forever. Never a fold-over.
      auto collapse_edge = [&](int i) {
        for (Halfedge h : {hs[i], mesh.opposite(hs[i])}) {
          const Point& target = mesh.position(mesh.to_vertex(h));
          if (collapse_geometry_ok(h, target, false, false, 0.5) && collapse_topology_ok(h) &&
              !collapse_crosses(h, target, false) &&
              collapse_keeps_fidelity(h, target, false, kSliverRepairToleranceTimes) &&
              collapse_with_mirror(h, false) != 0)
            return true;
        }
        return false;
      };
      auto flip_longest = [&]() {
        const Edge e = mesh.edge(hs[longest]);
        if (!repair_flip_ok(e) || !flip_geometry_ok(e, false)) return false;
        if (!flip_keeps_fidelity(e, kSliverRepairToleranceTimes)) return false;
        const Edge image = flip_partner(e);
        if (!image.is_valid() || (image != e && !mesh.is_flip_ok(image))) return false;
        mesh.flip(e);
        crossing_guard.flipped(mesh, e);
        if (image != e) {
          mesh.flip(image);
          crossing_guard.flipped(mesh, image);
        }
        return true;
      };
      const bool short_edge = len[shortest] < 0.2 * len[longest];
      bool done = (short_edge && collapse_edge(shortest)) || flip_longest();
      // A cap whose longest edge may not flip (a border or feature edge) goes by a collapse of one
      // of its two other edges, the shorter first: cgal/mask_cone.off's cone, cut open along a line,
      // kept a flat triangle at its apex between a border vertex and its two border neighbours.
      const int middle = 3 - shortest - longest;
      if (!done && !short_edge) done = collapse_edge(shortest);
      if (!done) done = collapse_edge(middle);
      // A flat cap on the border at a vertex with no other triangle: removed exactly (degenerate.cpp).
      if (!done && mirror_axis < 0 && mesh.is_boundary(mesh.edge(hs[longest])) && is_zero_area(f))
        done = remove_border_ear(hs[longest]);
      if (!done && merge_flat_across_features) done = collapse_flat_across_features(hs);
      fixed_this_pass += done;
    }
    fixed += fixed_this_pass;
    if (!fixed_this_pass) break;
  }
  return fixed;
}

}  // namespace adasculpt::remesh
