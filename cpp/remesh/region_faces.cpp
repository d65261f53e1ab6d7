// The faces a region iteration's crossing guard holds, and its undo of the relaxation's crossing
// moves: work proportional to the region, never to the mesh (a sculpting frame's budget).
#include "mesh/scratch.h"
#include "remesh/remesher_impl.h"

namespace adasculpt::remesh {

void Remesher::Impl::collect_region_faces() {
  region_faces.clear();
  mesh::resize_scratch(region_face_listed, mesh.faces_size(), std::uint8_t(0));
  const auto* hc = mesh.halfedge_connectivity_data();
  const Halfedge* vh = mesh.vertex_halfedge_data();
  const std::uint8_t* sc = scope.vector().data();
  auto list_fan = [&](Vertex v) {
    for_each_outgoing(hc, vh, v, [&](Halfedge h) {
      const Face f = hc[h.idx].face;
      if (f.is_valid() && !region_face_listed[f.idx]) {
        region_face_listed[f.idx] = 1;
        region_faces.push_back(f);
      }
    });
  };
  for (const Vertex v : scope_vertices) {
    if (mesh.is_deleted(v)) continue;
    list_fan(v);
    // The ring: the triangles an operation at v creates reach v's outside neighbours' faces.
    for_each_outgoing(hc, vh, v, [&](Halfedge h) {
      const Vertex w = hc[h.idx].to;
      if (sc[w.idx] == kOutside) list_fan(w);
    });
  }
  for (const Face f : region_faces) region_face_listed[f.idx] = 0;
}

// The list is the one the guard started with (the collapses and flips since then deleted some of
// its faces and rewrote others, but made none). Only scope vertices moved: their places before
// the relaxation are relaxed_from's, found through scope_at.
void Remesher::Impl::undo_region_crossing_moves() {
  mesh::resize_scratch(scope_at, mesh.vertices_size());
  for (size_t i = 0; i < scope_vertices.size(); ++i) scope_at[scope_vertices[i].idx] = static_cast<std::uint32_t>(i);
  const PlacesBefore before(mesh.positions().data(), scope_at, scope_vertices, relaxed_from);
  crossing_guard.undo_region_crossing_moves(mesh, before, region_faces);
}

}  // namespace adasculpt::remesh
