#pragma once
// The bounding box of one connected component of a mesh: the object under the brush, whose
// diagonal a stroke scales its detail settings by (Session). Measuring it is a walk over the whole
// component; the box then follows the edits from the vertices each one touched, so that after an
// undo or a redo the next stroke gets the diagonal a new walk would give (the same min and max,
// so the same bits) without the walk: on a one-object 1M-triangle scan the walk was a pass over the
// mesh at the first stroke after every undo (issue 18).
//
// Following an edit needs, besides the touched vertices' new positions, a vertex still at each of
// the box's six sides: one is kept per side, and when an edit moves it inward (or deletes it) the
// box is forgotten and the next stroke walks again.
#include <cstdint>
#include <vector>

#include "mesh/surface_mesh.h"

namespace adasculpt::sculpt {

class ComponentBox {
 public:
  // Walks the component holding v and returns its bounding-box diagonal; the box is followed from now on.
  double measure(const mesh::SurfaceMesh& m, mesh::Vertex v);
  // The diagonal measure(m, v) would return now, when v is in the followed component; 0 otherwise.
  double known_diagonal(const mesh::SurfaceMesh& m, mesh::Vertex v) const;
  // The mesh changed only at `touched`: vertices whose position or incident faces changed, deleted
  // ones allowed (a stroke's list), or left out when the edit deleted them (an undo's or a redo's).
  // Vertices of other components may be among them.
  void follow(const mesh::SurfaceMesh& m, const std::vector<mesh::Vertex>& touched);
  void forget() { followed_ = false; }
  // A new mesh: forgets, and sizes the per-vertex marks (no allocation in the first stroke).
  void reset(size_t vertex_slots);

 private:
  bool member(mesh::Vertex v) const { return v.idx < mark_.size() && mark_[v.idx] == run_; }
  void grow_marks(size_t vertex_slots);

  bool followed_ = false;
  Point lo_{0.0}, hi_{0.0};
  mesh::Vertex side_[6];               // a vertex at lo_ (axes 0-2) and at hi_ (3-5)
  std::vector<std::uint32_t> mark_;    // per vertex slot: == run_ for the followed component's vertices
  std::uint32_t run_ = 0;
  std::vector<mesh::Vertex> queue_;
};

}  // namespace adasculpt::sculpt
