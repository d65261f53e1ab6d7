// The crossing guard's shortcut for neighbours (geometry/embedded_fan.h): most faces near an
// operation's new triangles share a corner with them, and one test of that corner's fan as the
// operation would leave it clears all of those pairs at once (on bunny.off at the defaults,
// 96 % of the pairs the guard tested shared a corner).
#include <array>

#include "geometry/embedded_fan.h"
#include "remesh/crossing_guard.h"

namespace adasculpt::remesh {

namespace {
// One triangle (w, a, b) of a fan around w: the ring edge a -> b.
struct RingEdge {
  std::uint32_t a, b;
  Point pa;
};

// The ring edge of the triangle with corners ids at p opposite its corner w, and w's place;
// false when w is not a corner.
bool ring_edge(std::uint32_t w, const std::array<std::uint32_t, 3>& ids, const Point* p, RingEdge* edge,
               Point* centre) {
  for (int i = 0; i < 3; ++i)
    if (ids[i] == w) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      *edge = {ids[j], ids[k], p[j]};
      *centre = p[i];
      return true;
    }
  return false;
}
}  // namespace

bool CrossingGuard::fan_embedded_after(const SurfaceMesh& mesh, std::uint32_t w, const Candidate* ts, size_t n,
                                       Vertex replaced0, Vertex replaced1, Face skip0, Face skip1) const {
  constexpr size_t kMax = geometry::kMaxCertifiedValence;
  RingEdge edges[kMax];
  size_t k = 0;
  Point centre;
  bool centre_known = false;
  // The new triangles with corner w (those that exist already are among w's faces below).
  for (size_t i = 0; i < n; ++i) {
    if (ts[i].face.is_valid()) continue;
    if (k == kMax) return false;
    if (!ring_edge(w, ts[i].ids, ts[i].p, &edges[k], &centre)) continue;
    centre_known = true;
    ++k;
  }
  // w's faces that the operation keeps. (w is never a replaced vertex: the candidates name the
  // survivor of a collapse.)
  const Vertex v(w);
  if (v.idx >= mesh.vertices_size() || mesh.is_deleted(v)) return false;
  for (mesh::Halfedge out : mesh.halfedges(v)) {
    if (mesh.is_boundary(out)) return false;  // a border: left to the pair tests
    const Face f = mesh.face(out);
    if (f == skip0 || f == skip1) continue;
    const Vertex a = mesh.to_vertex(out), b = mesh.to_vertex(mesh.next(out));
    if (a == replaced0 || b == replaced0 || a == replaced1 || b == replaced1 || v == replaced0 || v == replaced1)
      continue;
    if (k == kMax) return false;
    edges[k++] = {a.idx, b.idx, mesh.position(a)};
    if (!centre_known) centre = mesh.position(v), centre_known = true;
  }
  if (k < 3 || !centre_known) return false;
  // The ring in order: from each edge's end to the edge that starts there, each edge once.
  Point ring[kMax];
  bool used[kMax] = {};
  size_t at = 0;
  used[0] = true;
  ring[0] = edges[0].pa;
  for (size_t step = 1; step < k; ++step) {
    size_t next = k;
    for (size_t e = 0; e < k; ++e)
      if (edges[e].a == edges[at].b) {
        next = e;
        break;
      }
    if (next == k || used[next]) return false;
    used[next] = true;
    ring[step] = edges[next].pa;
    at = next;
  }
  if (edges[at].b != edges[0].a) return false;
  return geometry::star_surely_embedded(centre, ring, k);
}

bool CrossingGuard::remembered_fan_embedded_after(const SurfaceMesh& mesh, std::uint32_t w, const Candidate* ts,
                                                  size_t n, Vertex replaced0, Vertex replaced1, Face skip0,
                                                  Face skip1) {
  for (const auto& [vertex, embedded] : fans_after_)
    if (vertex == w) return embedded;
  const bool embedded = fan_embedded_after(mesh, w, ts, n, replaced0, replaced1, skip0, skip1);
  fans_after_.push_back({w, embedded});
  return embedded;
}

bool CrossingGuard::shared_fan_embedded(const SurfaceMesh& mesh, const std::array<std::uint32_t, 3>& a,
                                        const std::array<std::uint32_t, 3>& b, const Candidate* ts, size_t n,
                                        Vertex replaced0, Vertex replaced1, Face skip0, Face skip1) {
  for (const std::uint32_t w : a)
    if ((w == b[0] || w == b[1] || w == b[2]) &&
        remembered_fan_embedded_after(mesh, w, ts, n, replaced0, replaced1, skip0, skip1))
      return true;
  return false;
}

}  // namespace adasculpt::remesh
