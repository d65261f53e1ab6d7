#pragma once
// MirrorTracker: find_mirror_map's answer for a mesh that changes a region at a time, kept up to
// date at the cost of the changes instead of a search over the whole mesh after each one (issue 18:
// 29-47 ms at 1.1M triangles for the first symmetric stroke after an undo, a grab or a one-sided
// stroke, and a pass over every vertex per stroke on a mesh that is not symmetric).
//
// It keeps the map per vertex slot, the set D of slots whose entries may be stale, and a
// PositionIndex of every live vertex. Invariant: every live vertex outside D is exactly at the
// mirror image of map[v]'s position, map[v] is live and outside D, and no other vertex outside D
// shares v's position. A change to slots T makes D grow by T and by the old images of T (so the
// invariant holds again: an untouched vertex whose image was untouched keeps both positions).
// Asking for the map then settles only D: each vertex of D must have exactly one vertex at its
// mirror position (an index probe) and that vertex must be in D (one outside D has a partner
// outside D at the same position as the D vertex: two vertices at one point, no map), and the
// entries must pair up. That is find_mirror_map's answer exactly: when every position is unique,
// the map is the one pairing there is.
//
// The mask (mesh/vertex_mask.h) must be its own mirror image for a stroke to mirror: the vertices
// whose mask differs from their image's are counted, and recounted on D when it is settled (a
// mask change at v changes the pairs of v and its image, both in D).
//
// A mesh that is not symmetric keeps a certificate: witness vertices with no vertex at their mirror
// positions (up to 16, spread over the slots). One stays valid while it is untouched and no vertex
// moves onto its mirror position, so each later question costs nothing until a change took them all. A mesh with two vertices at one
// point keeps the pair: while they are at one point, there is no map.
#include <cstdint>
#include <vector>

#include "geometry/position_index.h"
#include "mesh/surface_mesh.h"

namespace adasculpt::geometry {

class MirrorTracker {
 public:
  // Everything is forgotten (a change whose slots are not known): the next map() searches.
  void forget();
  // A new mesh, at its load (not interactive): everything is forgotten, and when the mesh's extent
  // along `axis` is symmetric the index is built and the whole map settled, so that the first
  // symmetric stroke after the load takes the map as later ones do (a search there was a 63-68 ms
  // hitch at 1.1M triangles). A lopsided extent leaves a witness and no index (most scans).
  void prepare(const mesh::SurfaceMesh& m, int axis);
  // The mesh changed at these slots (positions, liveness, slots appended or truncated; duplicates
  // and deleted ones allowed) since the last call. Nothing to do before the first map().
  void follow(const mesh::SurfaceMesh& m, const std::vector<mesh::Vertex>& touched);
  // As follow, for a change that kept the mesh exactly symmetric across the last map()'s plane and
  // whose map is known for every slot: the vector map() returned was lent out (the remesher
  // borrows it for a stroke) and came back holding it (updated by the stroke's splits and
  // collapses). Nothing is left to settle.
  void follow_with_map(const mesh::SurfaceMesh& m, const std::vector<mesh::Vertex>& touched);
  // find_mirror_map(m, axis) as it would answer now: the map (indexed by vertex slot; deleted
  // slots may hold anything), or nullptr when the mesh is not exactly symmetric across that plane.
  // The caller may move the vector's contents out (the remesher borrows it during a stroke) and
  // back, then tell which of follow_with_map, follow or forget_map applies (follow: it came back
  // not matching the mesh, but with the entries of every slot the change did not touch as they were).
  std::vector<mesh::Vertex>* map(const mesh::SurfaceMesh& m, int axis);
  // The lent map did not come back (or nothing is known of its entries): every entry is unknown
  // again (the index stays and still needs follow()).
  void forget_map();
  // After map() gave a map: every vertex's mask value equals its image's (true without a mask).
  bool mask_symmetric() const { return mask_odd_count_ == 0; }
  // Where map() keeps the map: a borrower moves it back here before follow_with_map.
  std::vector<mesh::Vertex>* lent_storage() { return &map_; }
  // Tests: how many vertices the last map() call had to settle (or read for the extent).
  size_t last_settled() const { return last_settled_; }

 private:
  void mark_unknown(mesh::Vertex v);
  void clear_unknown();
  struct Witness {
    mesh::Vertex v;
    Point p;  // its position when it was found
  };
  static constexpr size_t kMaxWitnesses = 16;
  bool witness_holds(const mesh::SurfaceMesh& m, const std::vector<mesh::Vertex>& touched, const Witness& w) const;
  void add_witness(mesh::Vertex v, const Point& p);
  bool find_extent_witness(const mesh::SurfaceMesh& m);
  bool settle(const mesh::SurfaceMesh& m);
  // settle's work once the index is built (fresh when `distinct`: its positions are distinct).
  bool settle_from_index(const mesh::SurfaceMesh& m, bool distinct);
  void recount_mask(const mesh::SurfaceMesh& m, const mesh::VertexProperty<float>& mask, mesh::Vertex v);
  void count_mask_everywhere(const mesh::SurfaceMesh& m);
  Point mirrored(Point p) const {
    p[axis_] = -p[axis_];
    return p;
  }

  int axis_ = -1;  // -1: nothing known (no index)
  PositionIndex index_;
  std::vector<mesh::Vertex> map_;
  // D: every live slot when all_unknown_ (a new mesh or axis, a lost map, or D grown past an
  // eighth of the mesh, where probing each vertex costs about what listing them would), else the
  // listed ones.
  bool all_unknown_ = true;
  std::vector<mesh::Vertex> unknown_;
  std::vector<std::uint8_t> in_unknown_;  // per slot: 1 when listed in unknown_
  bool coincidence_holds(const mesh::SurfaceMesh& m) const;
  std::vector<Witness> witnesses_;  // any of them: the mesh is not symmetric (see above)
  // Two vertices the last settle found at one point: while they are, there is no map (and no
  // witness either: the search's other way to fail), without settling anything again.
  mesh::Vertex coincident_[2];
  size_t last_settled_ = 0;
  std::vector<std::uint8_t> mask_odd_;  // per slot: 1 when live and its mask differs from its image's
  size_t mask_odd_count_ = 0;
};

}  // namespace adasculpt::geometry
