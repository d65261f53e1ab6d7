#pragma once
// PositionIndex: the vertex slots of a changing mesh by their exact position (bit for bit, -0 read
// as +0), so that "which vertices are exactly at p" costs a hash probe instead of a pass over the
// mesh. It follows the mesh through the lists of slots that changed (a stroke's touched vertices,
// an undo's swapped slots): each is taken out where it was filed and filed again under its
// position now, so keeping it costs the change, not the mesh. Built once per mesh (a pass).
//
// Open addressing with linear probing over a power-of-two table at most half full (8 bytes a
// bucket, 2-4 buckets a vertex, and 4 bytes a vertex slot); a removal
// shifts the entries behind it back instead of leaving a tombstone, so probes stay short however
// many changes it has followed.
#include <cstdint>
#include <vector>

#include "mesh/surface_mesh.h"

namespace adasculpt::geometry {

class PositionIndex {
 public:
  bool built() const { return !table_.empty(); }
  void clear();
  // Files every live vertex slot of m; false when two of them share a position.
  bool build(const mesh::SurfaceMesh& m);
  // These slots (duplicates, deleted ones and slots past the mesh's end allowed) may have moved,
  // appeared or gone: each is filed again as it is now. Slots the mesh dropped off its end (an undo
  // truncates its arrays) leave too.
  void update(const mesh::SurfaceMesh& m, const std::vector<mesh::Vertex>& slots);
  // How many live vertices are exactly at p; *first (when given) receives one of them, and *second
  // (when given) another one when there are several.
  int count_at(const mesh::SurfaceMesh& m, const Point& p, mesh::Vertex* first = nullptr,
               mesh::Vertex* second = nullptr) const;
  // The vertex at p when the caller knows positions are unique (stops at the first match).
  mesh::Vertex find(const mesh::SurfaceMesh& m, const Point& p) const;

 private:
  static constexpr std::uint32_t kEmpty = UINT32_MAX;
  // Returns false when a vertex at the same position was filed already.
  bool insert(const mesh::SurfaceMesh& m, std::uint32_t v);
  void erase(std::uint32_t v);
  void grow(const mesh::SurfaceMesh& m);

  // A bucket holds the slot and the low bits of its position's hash: a probe compares those
  // before reading a position (one cache miss per probe instead of one per bucket passed), and
  // a removal finds each entry's home bucket from them.
  struct Entry {
    std::uint32_t slot;  // kEmpty: a gap
    std::uint32_t key;
  };
  std::vector<Entry> table_;
  std::vector<std::uint32_t> home_;  // per vertex slot: its home bucket (filed there or after), kEmpty when not filed
  size_t filed_ = 0;
};

// Positions compared bit for bit, -0 read as +0 (the mirror plane's vertices may carry either):
// the equality find_mirror_map and the index use, and a hash that agrees with it.
bool same_position(const Point& a, const Point& b);
std::uint64_t position_hash(const Point& p);

}  // namespace adasculpt::geometry
