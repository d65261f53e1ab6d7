#pragma once
// FaceSlotTree: boxes over a changing mesh's face SLOTS for exact ray and closest-point queries
// that stay valid while strokes edit the mesh, at the cost of the change (TriangleTree is built
// for a fixed surface: rebuilding it after every stroke cost ~1 s at 1.1M triangles).
//
// Leaves hold 16 slots: when the tree is built, the live slots are sorted along a Morton curve of
// their centroids; slots added later follow in slot order (a stroke adds them all in its region).
// 16 boxes make a box of the next level, and so on. The owner reports what changed (mark_vertex:
// a vertex moved or its faces changed, mark_face: a face slot changed or was deleted); sync() then
// refits only the leaves of those slots and the boxes above them, and takes in the slots added or
// removed at the end of the mesh since (an undo truncates the arrays). The queries read the mesh
// itself, so sync() must run after the last change and before a query.
//
// Answers are exact and independent of the boxes: the nearest hit (ray) or point (closest), and
// among equally near ones the lowest face slot, as a scan of every live face would give.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mesh/surface_mesh.h"
#include "mesh/types.h"

namespace adasculpt::geometry {

class FaceSlotTree {
 public:
  struct Hit {
    mesh::Face face;  // invalid when nothing was found
    Point point{0.0};
    double bary[3] = {0, 0, 0};
    double t = 0;          // ray: the point is at origin + t * dir (computed on the triangle)
    double distance2 = 0;  // closest point: squared distance from the query
  };

  // Everything is rebuilt (sorted and fitted) at the next sync(): a new mesh.
  void invalidate() { built_ = false; }
  // v moved, or the faces around it changed: the leaves of its faces are refitted.
  void mark_vertex(const mesh::SurfaceMesh& m, mesh::Vertex v);
  // Face slot f may hold another triangle (or none): its leaf is refitted.
  void mark_face(mesh::Face f);
  void sync(const mesh::SurfaceMesh& m);

  // Nearest intersection with t >= 0 of origin + t * dir, either side.
  Hit intersect_ray(const mesh::SurfaceMesh& m, const Point& origin, const Vec3& dir) const;
  // Nearest point of the surface. face invalid when the mesh has no face.
  Hit closest_point(const mesh::SurfaceMesh& m, const Point& q) const;

  // Leaves refitted by the last sync() (tests: the work follows the change, not the mesh).
  size_t last_refit() const { return last_refit_; }

 private:
  static constexpr std::uint32_t kFan = 16;  // slots per leaf, boxes per parent
  struct Box {
    Point lo, hi;
  };
  struct Level {
    std::vector<Box> boxes;
    std::vector<std::uint8_t> mark;
    std::vector<std::uint32_t> dirty;
  };

  void build(const mesh::SurfaceMesh& m);
  void take_new_slots(const mesh::SurfaceMesh& m);
  void resize_levels();
  void mark_leaf(std::uint32_t leaf);
  void fit_leaf(const mesh::SurfaceMesh& m, std::uint32_t leaf);
  void fit_parent(size_t level, std::uint32_t b);
  // Boxes [first, end) of `level`, nearest first by key(box) (negative: missed), while their key
  // does not pass `best` (lowered by test(slot) as it finds better answers).
  template <class Key, class Test>
  void search(const mesh::SurfaceMesh& m, size_t level, std::uint32_t first, std::uint32_t end, const Key& key,
              const Test& test, const double& best) const;

  bool built_ = false;
  std::vector<std::uint32_t> order_;  // slots in leaf order
  std::vector<std::uint32_t> rank_;   // slot -> place in order_
  size_t synced_faces_ = 0;           // the mesh's face slots at the last sync()
  std::vector<Level> levels_;         // [0] = leaves
  std::vector<mesh::Face> pending_faces_;  // marked before the slots were taken in
  size_t last_refit_ = 0;
};

}  // namespace adasculpt::geometry
