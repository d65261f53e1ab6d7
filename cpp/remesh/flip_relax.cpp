// Connectivity and position passes of a remeshing iteration: valence-driven edge flips and
// the paper's area-and-sizing weighted tangential relaxation (equation 6), then projection.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "geometry/portable_math.h"
#include "geometry/triangle.h"
#include "remesh/remesher_impl.h"

namespace adasculpt::remesh {

namespace {
int target_valence(const SurfaceMesh& m, Vertex v) { return m.is_boundary(v) ? 4 : 6; }
int sq(int x) { return x * x; }
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
  if (!require_flat) return true;
  // The new triangles must agree with each other at least as well as the old ones did.
  double old_cos = (l1 > 0 && l2 > 0) ? glm::dot(n1, n2) / (l1 * l2) : -1.0;
  double new_cos = glm::dot(m1, m2) / (k1 * k2);
  return new_cos >= std::min(old_cos, 0.9) - 1e-12 && new_cos > 0.5;
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

// Uses scope_edges as collapse_short_edges left them (collapses delete edges but create none).
size_t Remesher::Impl::flip_edges() {
  valence.resize(mesh.vertices_size());
  for (Vertex v : scope_vertices)
    if (!mesh.is_deleted(v)) valence[v.idx] = static_cast<int>(mesh.valence(v));
  size_t flips = 0;
  for (Edge e : scope_edges) {
    if (mesh.is_deleted(e) || is_feature(e) || mesh.is_boundary(e)) continue;
    Halfedge h = mesh.halfedge(e, 0), o = mesh.halfedge(e, 1);
    Vertex a = mesh.to_vertex(o), b = mesh.to_vertex(h);
    Vertex c = mesh.to_vertex(mesh.next(h)), d = mesh.to_vertex(mesh.next(o));
    // All four corners must be in the iteration's scope; held border vertices may gain or
    // lose an edge, outside vertices may not.
    if (scope[c] == kOutside || scope[d] == kOutside) continue;
    int va = valence[a.idx], vb = valence[b.idx], vc = valence[c.idx], vd = valence[d.idx];
    int ta = target_valence(mesh, a), tb = target_valence(mesh, b), tc = target_valence(mesh, c),
        td = target_valence(mesh, d);
    int before = sq(va - ta) + sq(vb - tb) + sq(vc - tc) + sq(vd - td);
    int after = sq(va - 1 - ta) + sq(vb - 1 - tb) + sq(vc + 1 - tc) + sq(vd + 1 - td);
    if (after >= before) continue;
    if (!flip_topology_ok(e) || !flip_geometry_ok(e, true)) continue;
    mesh.flip(e);
    --valence[a.idx];
    --valence[b.idx];
    ++valence[c.idx];
    ++valence[d.idx];
    ++flips;
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
  face_quality.resize(mesh.faces_size());
  auto quality_of = [&](mesh::Face f) {
    Vertex c[3];
    mesh.face_vertices(f, c);
    return min_angle_sin2(mesh.position(c[0]), mesh.position(c[1]), mesh.position(c[2]));
  };
  if (whole_mesh) {
    for (mesh::Face f : mesh.faces()) face_quality[f.idx] = quality_of(f);
  } else {
    for (Edge e : scope_edges)
      for (unsigned i = 0; i < 2 && !mesh.is_deleted(e); ++i) {
        mesh::Face f = mesh.face(mesh.halfedge(e, i));
        if (f.is_valid()) face_quality[f.idx] = quality_of(f);
      }
  }
  size_t flips = 0;
  for (Edge e : scope_edges) {
    if (mesh.is_deleted(e) || is_feature(e) || mesh.is_boundary(e)) continue;
    Halfedge h = mesh.halfedge(e, 0), o = mesh.halfedge(e, 1);
    mesh::Face f1 = mesh.face(h), f2 = mesh.face(o);
    double before = std::min(face_quality[f1.idx], face_quality[f2.idx]);
    if (before >= poor_sin2) continue;
    Vertex va = mesh.to_vertex(o), vb = mesh.to_vertex(h);
    Vertex vc = mesh.to_vertex(mesh.next(h)), vd = mesh.to_vertex(mesh.next(o));
    if (scope[vc] == kOutside || scope[vd] == kOutside) continue;
    const Point &a = mesh.position(va), &b = mesh.position(vb), &c = mesh.position(vc), &d = mesh.position(vd);
    // Delaunay test: the angles gamma, delta opposite the edge sum to more than pi, i.e.
    // sin(gamma + delta) < 0 (both lie in (0, pi)); no trigonometric calls needed.
    Vec3 ca = a - c, cb = b - c, da = a - d, db = b - d;
    double sin_sum = glm::length(glm::cross(ca, cb)) * glm::dot(da, db) + glm::dot(ca, cb) * glm::length(glm::cross(da, db));
    if (sin_sum >= 0) continue;
    double q1 = min_angle_sin2(a, d, c), q2 = min_angle_sin2(d, b, c);
    if (std::min(q1, q2) <= before) continue;
    if (!flip_topology_ok(e) || !flip_geometry_ok(e, true)) continue;
    mesh.flip(e);
    --valence[va.idx];
    --valence[vb.idx];
    ++valence[vc.idx];
    ++valence[vd.idx];
    // flip() keeps the face slots: f1 is now (a, d, c), f2 is (d, b, c).
    face_quality[f1.idx] = q1;
    face_quality[f2.idx] = q2;
    ++flips;
  }
  return flips;
}

void Remesher::Impl::relax_vertices() {
  new_positions.resize(scope_vertices.size());
  for (size_t i = 0; i < scope_vertices.size(); ++i) {
    Vertex v = scope_vertices[i];
    if (mesh.is_deleted(v)) continue;
    const Point p = mesh.position(v);
    new_positions[i] = p;
    if (!movable(v)) continue;
    if (vclass[v] == kFeatureLine) {
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
    double weight = 0;
    for (Halfedge h : mesh.halfedges(v)) {
      if (mesh.is_boundary(h)) continue;
      Vertex w1 = mesh.to_vertex(h), w2 = mesh.to_vertex(mesh.next(h));
      const Point& p1 = mesh.position(w1);
      const Point& p2 = mesh.position(w2);
      Vec3 n = glm::cross(p1 - p, p2 - p);
      double area = 0.5 * glm::length(n);
      double size = (sizing[v] + sizing[w1] + sizing[w2]) / 3.0;
      double w = area * size;
      normal += n;
      c += w * (p + p1 + p2) / 3.0;
      weight += w;
    }
    double nl = glm::length(normal);
    if (weight <= 0 || nl <= 0) continue;
    normal /= nl;
    Vec3 u = c / weight - p;
    new_positions[i] = p + (u - normal * glm::dot(normal, u));
  }
  for (size_t i = 0; i < scope_vertices.size(); ++i) {
    Vertex v = scope_vertices[i];
    if (!mesh.is_deleted(v) && movable(v)) mesh.position(v) = new_positions[i];
  }
}

void Remesher::Impl::project_vertices() {
  for (Vertex v : scope_vertices)
    if (!mesh.is_deleted(v) && movable(v)) project(v);
}

// Removes triangles with an angle below `angle_deg` (zero-area and needle triangles of the
// input, and the rare sliver the regular passes could not avoid): collapse their shortest edge
// when it is short, otherwise flip their longest edge (a "cap" has no short edge).
size_t Remesher::Impl::fix_bad_faces(double angle_deg) {
  const double sin_limit = portable::sin(angle_deg * M_PI / 180.0);
  const double sin2_limit = sin_limit * sin_limit;
  size_t fixed = 0;
  for (int pass = 0; pass < 3; ++pass) {
    size_t fixed_this_pass = 0;
    faces_scratch.clear();
    if (whole_mesh) {
      for (mesh::Face f : mesh.faces()) faces_scratch.push_back(f);
    } else {
      // Each face once: from its first active corner in halfedge order.
      for (Vertex v : scope_vertices) {
        if (mesh.is_deleted(v) || scope[v] != kActive) continue;
        for (Halfedge h : mesh.halfedges(v)) {
          if (mesh.is_boundary(h)) continue;
          Vertex prev_corner = mesh.from_vertex(mesh.prev(h));  // the corner before v
          Vertex next_corner = mesh.to_vertex(h);
          bool earlier = (scope[prev_corner] == kActive && prev_corner.idx < v.idx) ||
                         (scope[next_corner] == kActive && next_corner.idx < v.idx);
          if (!earlier) faces_scratch.push_back(mesh.face(h));
        }
      }
    }
    for (mesh::Face f : faces_scratch) {
      if (mesh.is_deleted(f)) continue;
      Halfedge hs[3] = {mesh.halfedge(f), mesh.next(mesh.halfedge(f)), mesh.prev(mesh.halfedge(f))};
      Point p[3];
      for (int i = 0; i < 3; ++i) p[i] = mesh.position(mesh.to_vertex(hs[i]));
      if (min_angle_sin2(p[0], p[1], p[2]) >= sin2_limit) continue;
      // Edge lengths: hs[i] runs from p[(i+2)%3] to p[i].
      double len[3];
      for (int i = 0; i < 3; ++i) len[i] = glm::length(p[i] - p[(i + 2) % 3]);
      int shortest = int(std::min_element(len, len + 3) - len);
      int longest = int(std::max_element(len, len + 3) - len);
      bool done = false;
      if (len[shortest] < 0.2 * len[longest]) {
        // A sliver's neighbours may end up a little beyond the split threshold, and its fan may
        // turn by up to 90 degrees (folded input such as self-intersections): accepted here, the
        // next passes even that out, while the sliver would stay forever. Never a fold-over.
        for (Halfedge h : {hs[shortest], mesh.opposite(hs[shortest])})
          if (collapse_geometry_ok(h, mesh.position(mesh.to_vertex(h)), false, false, 0.5) &&
              collapse_topology_ok(h)) {
            Halfedge o = mesh.opposite(h);
            if (!mesh.is_boundary(h)) feature[mesh.edge(mesh.prev(h))] |= feature[mesh.edge(mesh.next(h))];
            if (!mesh.is_boundary(o)) feature[mesh.edge(mesh.next(o))] |= feature[mesh.edge(mesh.prev(o))];
            mesh.collapse(h);
            done = true;
            break;
          }
      }
      if (!done) {
        Edge e = mesh.edge(hs[longest]);
        if (!is_feature(e) && !mesh.is_boundary(e) && in_scope(e) && mesh.is_flip_ok(e) &&
            flip_geometry_ok(e, false)) {
          mesh.flip(e);
          done = true;
        }
      }
      fixed_this_pass += done;
    }
    fixed += fixed_this_pass;
    if (!fixed_this_pass) break;
  }
  return fixed;
}

}  // namespace adasculpt::remesh
