// Remesher::reset_slots: a kept remesher brought back to the state a new one would start in, around
// the slots that changed behind its back (an undo or redo swapped them) or under its own passes
// (a stroke deformed them, so the dihedral angles its feature marks came from are stale). Only the
// neighbourhood of those slots is visited: a new remesher's marks cost a pass over every edge
// (5.8 ms at 1.1M triangles, the first stroke after every undo; issue 18).
#include <algorithm>
#include <cstdint>
#include <vector>

#include "remesh/remesher_impl.h"

namespace adasculpt::remesh {

void Remesher::reset_slots(const std::vector<Vertex>& vertices) {
  Impl& m = *impl_;
  const size_t n = m.mesh.vertices_size();
  // The values a new remesher gives every vertex slot (the arrays' defaults in Impl::Impl); the
  // classes follow from the marks, below.
  for (Vertex v : vertices) {
    if (v.idx >= n) continue;
    m.sizing[v] = 0.0;
    m.scope[v] = kOutside;
    m.ref_hint[v] = UINT32_MAX;
    m.segment_hint[v] = UINT32_MAX;
  }
  m.region_calls_since_sizing = 0;
  m.sizing_spread = false;
  m.refresh_marks_around(vertices);
}

// What mark_features (with drop_isolated_features) leaves on e, from e's neighbourhood alone: its
// raw mark, dropped when it is an interior edge whose two ends have no other raw mark, or one of
// three interior edges of a face whose corners have exactly two raw marks each. (That loop test
// runs after the first drop, but a corner with two marks drops none of its edges there.)
bool Remesher::Impl::marked_as_new(Edge e, double cos_limit) const {
  if (!sharp_or_boundary(e, cos_limit)) return false;
  if (mesh.is_boundary(e)) return true;
  const auto* hc = mesh.halfedge_connectivity_data();
  const Halfedge* vh = mesh.vertex_halfedge_data();
  auto raw_count = [&](Vertex v) {
    int count = 0;
    for_each_outgoing(hc, vh, v, [&](Halfedge h) { count += sharp_or_boundary(SurfaceMesh::edge(h), cos_limit); });
    return count;
  };
  const int count_a = raw_count(mesh.vertex(e, 0)), count_b = raw_count(mesh.vertex(e, 1));
  if (count_a == 1 && count_b == 1) return false;
  if (count_a != 2 || count_b != 2) return true;
  for (unsigned side = 0; side < 2; ++side) {
    const Halfedge h = mesh.halfedge(e, side);
    const Halfedge g1 = mesh.next(h), g2 = mesh.next(g1);
    bool isolated_loop = true;
    for (Halfedge g : {g1, g2}) {
      const Edge ge = mesh.edge(g);
      isolated_loop = isolated_loop && !mesh.is_boundary(ge) && sharp_or_boundary(ge, cos_limit);
    }
    if (isolated_loop && raw_count(mesh.to_vertex(g1)) == 2) return false;
  }
  return true;
}

// The marks of an edge depend on the faces at its ends and at the far corners of its faces, a
// vertex's class on the marks at it. A changed vertex (set V0) changes the raw marks of its faces'
// edges, and so the raw counts at the vertices of those faces (V1: V0 and its neighbours); the
// drops can then change on the edges of the faces at V1, and the classes at those faces' corners.
// Everything beyond keeps the values a new remesher gives it, by induction from the last reset.
void Remesher::Impl::refresh_marks_around(const std::vector<Vertex>& vertices) {
  const size_t n = mesh.vertices_size();
  // kappa_known (all zero between uses) marks the vertices listed in reset_ring.
  mesh::resize_scratch(kappa_known, n, std::uint8_t(0));
  mesh::resize_scratch(face_seen, mesh.faces_size(), 0u);
  if (++face_run == 0) {
    std::fill(face_seen.begin(), face_seen.end(), 0u);
    face_run = 1;
  }
  const auto* hc = mesh.halfedge_connectivity_data();
  const Halfedge* vh = mesh.vertex_halfedge_data();
  std::uint8_t* listed = kappa_known.data();
  reset_ring.clear();
  auto list = [&](Vertex v) {
    if (listed[v.idx]) return;
    listed[v.idx] = 1;
    reset_ring.push_back(v);
  };
  for (Vertex v : vertices)
    if (v.idx < n && !mesh.is_deleted(v)) list(v);
  const size_t changed = reset_ring.size();
  for (size_t i = 0; i < changed; ++i)
    for_each_outgoing(hc, vh, reset_ring[i], [&](Halfedge h) { list(hc[h.idx].to); });
  const size_t first_ring = reset_ring.size();
  const double cos_limit = feature_cos_limit();
  const bool features_on = cos_limit <= 1.0;  // off (the sculpting default): the marks are the boundary
  std::uint8_t* feat = feature.vector().data();
  for (size_t i = 0; i < first_ring; ++i)
    for_each_outgoing(hc, vh, reset_ring[i], [&](Halfedge h) {
      const mesh::Face f = hc[h.idx].face;
      if (!f.is_valid() || face_seen[f.idx] == face_run) return;
      face_seen[f.idx] = face_run;
      Halfedge g = h;
      for (int k = 0; k < 3; ++k, g = hc[g.idx].next) {
        const mesh::Index e = g.idx >> 1;
        feat[e] = features_on ? marked_as_new(Edge(e), cos_limit)
                              : !hc[e << 1].face.is_valid() || !hc[(e << 1) | 1u].face.is_valid();
        list(hc[g.idx].to);
      }
    });
  // Every edge at these vertices now holds its new mark (refreshed above, or unchanged).
  for (Vertex v : reset_ring) {
    int count = 0;
    for_each_outgoing(hc, vh, v, [&](Halfedge h) { count += feat[h.idx >> 1] != 0; });
    vclass[v] = vertex_class(count);
    listed[v.idx] = 0;
  }
}

}  // namespace adasculpt::remesh
