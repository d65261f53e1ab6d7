#pragma once
// Walking a vertex's fan on the mesh's flat connectivity arrays. The per-frame passes of a
// sculpting stroke (the brushes' gathers, the remesher's region passes) walk every fan of the
// region several times; through the circulators each step reloads the property arrays' data
// pointers (the compiler cannot prove a store does not change them), on these pointers it does not.
#include "mesh/surface_mesh.h"

namespace adasculpt::mesh {

// Calls fn(h) for every outgoing halfedge h of v, in the order of mesh.halfedges(v).
// hc = mesh.halfedge_connectivity_data(), vh = mesh.vertex_halfedge_data(): valid until the
// mesh gains elements.
template <class Fn>
inline void for_each_outgoing(const SurfaceMesh::HalfedgeConnectivity* hc, const Halfedge* vh, Vertex v, Fn&& fn) {
  const Halfedge start = vh[v.idx];
  if (!start.is_valid()) return;
  Halfedge h = start;
  do {
    fn(h);
    h = hc[h.idx ^ 1u].next;
  } while (h != start);
}

}  // namespace adasculpt::mesh
