// Geometric safety of the remeshing operations (issue 17 item 2): the measures the guards of
// the passes share.
#include <glm/geometric.hpp>

#include "remesh/remesher_impl.h"

namespace adasculpt::remesh {

// Which way v's surface faces, for choosing its own sheet of a thin part when projecting
// (reference.cpp). Read from the flat arrays: called once per projected vertex.
Vec3 Remesher::Impl::fan_normal(Vertex v) const {
  const auto* hc = mesh.halfedge_connectivity_data();
  const Halfedge* vh = mesh.vertex_halfedge_data();
  const Point* pos = mesh.positions().data();
  const Point& p = pos[v.idx];
  Vec3 n(0.0);
  for_each_outgoing(hc, vh, v, [&](Halfedge h) {
    if (!hc[h.idx].face.is_valid()) return;
    const Point& a = pos[hc[h.idx].to.idx];
    const Point& b = pos[hc[hc[h.idx].next.idx].to.idx];
    n += glm::cross(a - p, b - p);
  });
  return n;
}

}  // namespace adasculpt::remesh
