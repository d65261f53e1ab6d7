#pragma once
// Which part of a grab's region each frame's remeshing iteration works on (issue 18: the frame-
// time tail). A pull moves every vertex of its ROI, but most of them hardly change shape: the
// handle translates rigidly, and near the ROI's border the field is flat. Remeshing all of them
// every frame (the paper's scheme) cost as much as the field's solve and the rest of the frame
// together.
//
// RegionStrain keeps, per vertex of the region, the position it had at the end of the last frame
// and the strain accumulated since the remesher last worked on it. A frame's strain at a vertex v
// is the largest relative change of an edge vector around it,
//   max over neighbours n of |d(n) - d(v)| / |p(n) - p(v)|,   d = the frame's displacement:
// 0 for a translation, about the stretch for a stretch and the angle for a bend (or a rotation, so
// a twist is remeshed as before). A vertex is active when its accumulated strain reaches the
// threshold, when it has no position from the last frame (new, or new to the region; the first
// frame: all of them), when such a vertex is its neighbour, or when the last frame's iteration
// changed its valence (the remesher is still at work there). The scope of the frame's remeshing is
// the active vertices and kScopeRings rings around them (the outer ring holds the scope's border,
// Remesher::iterate_region, so the active vertices' neighbours are still relaxed); the active
// vertices' strain starts again from 0.
//
// With threshold 0 every vertex is active: the scope is the whole region, as in the paper.
#include <cstdint>
#include <vector>

#include "mesh/surface_mesh.h"

namespace adasculpt::sculpt {

class RegionStrain {
 public:
  // With one ring, the vertices next to the active ones were held and the triangles between them
  // and the rest degraded: the held-out pull ended with 10x as many triangles under 30 degrees as
  // with the whole region; two rings keep it within 3x (and the dragon's the same).
  static constexpr int kScopeRings = 2;

  // A new grab: nothing is known about any vertex.
  void reset();
  // After the frame's deformation: the scope of its remeshing iteration, from `region` (the
  // deformer's ROI plus ring, live vertices). Fills `scope` (a subset of region, in its order).
  void select(const mesh::SurfaceMesh& mesh, const std::vector<mesh::Vertex>& region, double threshold,
              std::vector<mesh::Vertex>& scope);
  // After the remeshing iteration: `region` (the deformer's list) loses the vertices the
  // iteration removed and gains those it added (they are in `scope`, which the remesher updated);
  // the vertices it added or whose valence it changed stay in the next scope; then every vertex of
  // the region records its position for the next frame. (A release calls select_release instead
  // of select, and this with its footprint as the region.)
  void update_region(const mesh::SurfaceMesh& mesh, std::vector<mesh::Vertex>& region,
                     const std::vector<mesh::Vertex>& scope);
  // The release's scope (sculpt/grab.h), within `footprint` (every vertex the grab's regions held,
  // live): the vertices the last iteration left unsettled and the corners of the triangles under
  // `poor_angle_deg` there, and kScopeRings rings around them. Nothing moves any more, so strain
  // plays no part. Then update_region(mesh, footprint, scope) after the iteration, as for a frame.
  void select_release(const mesh::SurfaceMesh& mesh, const std::vector<mesh::Vertex>& footprint,
                      double poor_angle_deg, std::vector<mesh::Vertex>& scope);

 private:
  // scope = the vertices in front_ (stamped in scope_stamp_) and kScopeRings rings around them
  // within this frame's region, in the region's order.
  void grow_scope(const mesh::SurfaceMesh& mesh, const std::vector<mesh::Vertex>& region,
                  std::vector<mesh::Vertex>& scope);
  void grow(size_t n);
  bool known(mesh::Vertex v) const { return seen_[v.idx] == frame_; }

  // Per vertex slot, never cleared: an entry counts when its stamp equals frame_.
  std::uint32_t frame_ = 1;
  std::vector<std::uint32_t> seen_;         // position_ holds the end of the last frame
  std::vector<Point> position_;
  std::vector<Vec3> displacement_;          // this frame's (where known)
  std::vector<float> strain_;               // accumulated since last in an active set
  std::vector<std::uint32_t> in_region_;    // in this frame's region
  std::vector<std::uint32_t> scope_stamp_;  // in this frame's scope
  std::vector<float> edge_strain2_;         // this frame's largest squared edge strain (select)
  std::vector<std::uint8_t> next_to_new_;   // this frame: an edge to a vertex without a last position
  std::vector<std::uint32_t> unsettled_;    // the last iteration changed its connectivity
  std::vector<std::uint16_t> valence_;      // before this frame's iteration (region vertices)
  std::vector<mesh::Vertex> front_, next_front_;  // the rings' breadth-first search
};

}  // namespace adasculpt::sculpt
