#pragma once
// RenderBuffers: the float32/uint32 arrays a GPU draws, kept in step with a SurfaceMesh that
// changes a little every frame. One entry per vertex SLOT and per face SLOT (deleted slots
// included, so handles index the buffers directly while a grab leaves garbage in the mesh);
// a deleted face is written as (0,0,0), which draws nothing.
//
// Capacity grows geometrically, so pointers (and typed-array views in the browser) stay valid
// until an update reports `reallocated`. After warm-up, update() allocates nothing: it rewrites
// the touched vertices, the normals of their one-ring, and (when the topology changed) the faces
// around touched vertices, the touched faces and the new face slots, and reports the dirty
// ranges so the renderer uploads only those. Work is proportional to the change, not to the
// mesh: no pass over the slots, not even over the deletion flags (last_work() counts it).
//
// Fewer slots than the last update (an undo takes back the slots its step appended) empties the
// triangles of the face slots past the new count, also incrementally.
//
// Contract for incremental updates: every live face whose triangle changed has a touched live
// vertex (the old or the new triangle's), and every face deleted since the last update is in
// the touched faces (a deleted face is reachable from no vertex). The session satisfies it: the
// remesher only edits edges with both ends in the region (a flip's old edge ends, a collapse's
// survivor, a split's new vertex), new vertices join the region, and the collapses and undo
// steps list the face slots they delete (ChangeSet::touched_faces).
#include <cfloat>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mesh/surface_mesh.h"

namespace adasculpt::sculpt {

// What one or several updates changed. Ranges are half-open slot ranges [begin, end); an empty
// range has begin == end. vertex_count / face_count are the slot counts to draw.
struct RenderChanges {
  bool reallocated = false;      // capacity grew: every earlier pointer/view is stale, re-read all
  bool indices_changed = false;  // some face slot got another triangle (or was added/deleted)
  std::uint32_t vertex_begin = 0, vertex_end = 0;
  std::uint32_t face_begin = 0, face_end = 0;
  std::uint32_t vertex_count = 0, face_count = 0;
  // Axis-aligned box of every position written (empty: min > max), and whether a rebuild wrote
  // all of them. A viewer keeps the mesh's bounds by growing them with the box (starting over
  // after a rebuild) instead of a pass over every vertex per stroke; the bounds may then be a
  // little larger than the mesh (vertices moved inwards or deleted), which culling tolerates.
  bool rebuilt = false;
  float box_min[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, box_max[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};

  bool empty() const { return !reallocated && vertex_begin == vertex_end && face_begin == face_end; }
  // Marks all `vertices` and `faces` slots dirty (and the indices changed).
  void everything(std::uint32_t vertices, std::uint32_t faces);
  // Union of two reports, this one first (counts are the later ones).
  void merge(const RenderChanges& later);
};

class RenderBuffers {
 public:
  RenderBuffers() = default;

  // Rewrites everything from the mesh.
  const RenderChanges& rebuild(const mesh::SurfaceMesh& m);
  // Incremental update. `touched` are vertices whose positions or incident faces may have changed
  // and `faces` face slots that may have changed, the deleted ones at least (both may contain
  // duplicates and deleted elements; see the contract above); topology_changed says faces were
  // added, removed or flipped; everything forces a rebuild. Returns this update's changes (also
  // merged into pending()).
  const RenderChanges& update(const mesh::SurfaceMesh& m, const mesh::Vertex* touched, size_t n_touched,
                              const mesh::Face* faces, size_t n_faces, bool topology_changed, bool everything);
  // The same from a sculpt::ChangeSet (a template so this header needs no Session).
  template <class ChangeSetT>
  const RenderChanges& update(const mesh::SurfaceMesh& m, const ChangeSetT& c) {
    return update(m, c.touched_vertices.data(), c.touched_vertices.size(), c.touched_faces.data(),
                  c.touched_faces.size(), c.topology_changed, c.everything);
  }
  // Vertex and face slots the last update read or wrote (positions, normals, triangles): the
  // tests check that it follows the change, not the mesh.
  size_t last_work() const { return work_; }

  // Changes accumulated since the last take_pending(): a renderer that does not read after every
  // update still uploads everything that changed.
  const RenderChanges& pending() const { return pending_; }
  RenderChanges take_pending();

  // The face slots whose drawn triangle may differ from the one at the previous take_pending():
  // its corners or their positions changed (duplicates possible), so a picking structure over the
  // slots (web/slot-ray-tree.js) refits only those. Listed by each update() as it writes them: the
  // faces around the touched vertices, the rewritten slots and the emptied ones. all_faces_dirty()
  // instead when a rebuild, a reallocation or a list longer than the slots made them all dirty.
  // take_pending() hands them over: valid until the next take_pending().
  const std::uint32_t* dirty_faces() const { return taken_dirty_faces_.data(); }
  size_t dirty_face_count() const { return taken_dirty_faces_.size(); }
  bool all_faces_dirty() const { return taken_all_dirty_; }

  const float* positions() const { return positions_.data(); }  // xyz per vertex slot
  const float* normals() const { return normals_.data(); }      // xyz per vertex slot, unit length
  const std::uint32_t* indices() const { return indices_.data(); }  // 3 per face slot
  // The mask (mesh/vertex_mask.h) per vertex slot, 0 without one: written with the positions, so
  // a mask operation that reports its changed vertices as touched updates it incrementally.
  const float* masks() const { return masks_.data(); }
  std::uint32_t vertex_count() const { return vertex_count_; }
  std::uint32_t face_count() const { return face_count_; }
  size_t vertex_capacity() const { return positions_.size() / 3; }
  size_t face_capacity() const { return indices_.size() / 3; }

 private:
  bool reserve(size_t vertex_slots, size_t face_slots);  // true when it reallocated
  void mark_normal(mesh::Vertex v);                     // queue v for a normal refresh (deduplicated)
  void write_position(const mesh::SurfaceMesh& m, mesh::Vertex v);
  void write_normal(const mesh::SurfaceMesh& m, mesh::Vertex v);
  bool write_face(const mesh::SurfaceMesh& m, mesh::Face f);  // true when the stored triple changed

  std::vector<float> positions_, normals_, masks_;
  mesh::VertexProperty<float> mask_;  // the mesh's, looked up by each rebuild() / update()
  std::vector<std::uint32_t> indices_;
  std::uint32_t vertex_count_ = 0, face_count_ = 0;
  size_t work_ = 0;
  // Deduplication of the normal refresh list without clearing a per-vertex array each frame.
  std::vector<std::uint32_t> stamp_;
  std::uint32_t epoch_ = 0;
  std::vector<mesh::Vertex> normal_queue_;
  RenderChanges last_, pending_;
  void mark_face_dirty(std::uint32_t slot);
  std::vector<std::uint32_t> dirty_faces_, taken_dirty_faces_;  // pending, and handed over
  bool all_dirty_ = true, taken_all_dirty_ = true;
};

}  // namespace adasculpt::sculpt
