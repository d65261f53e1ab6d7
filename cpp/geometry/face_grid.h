#pragma once
// A hash grid of a changing mesh's face bounding boxes: which faces may touch a given box. Built
// once over every live face; a face whose box changes (a collapse, flip or vertex move) is
// inserted again, and its entries with the old box stay behind as harmless stale candidates
// (callers test the face's current geometry). The arrays are reused from one build to the next,
// so once warmed up neither building nor updating allocates.
//
// A bounding volume hierarchy answers the same question but must be refitted or rebuilt after
// each edit; cells answer it at the cost of one append per cell the new box covers.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "mesh/surface_mesh.h"
#include "mesh/types.h"

namespace adasculpt::geometry {

class FaceGrid {
 public:
  // Every live face of the mesh, in cells of the given edge length (> 0).
  void build(const mesh::SurfaceMesh& mesh, double cell_size);
  // Only the listed live faces (a sculpting frame's region and the ring around it), at a cost
  // proportional to the list: its scratch is indexed by list position (a face's key), but for a
  // map from face slot to position (4 bytes a slot, reserve_listed). Such a grid never rebuilds
  // itself (a rebuild would list the whole mesh): its inserts that leave their cells go to the
  // overflow lists, which a region's few operations keep short.
  void build(const mesh::SurfaceMesh& mesh, double cell_size, const std::vector<mesh::Face>& faces);
  // Sizes the per-face-slot arrays a listed build and its queries use for a mesh of this many
  // face slots (no allocation in a frame but for the slots the frame adds).
  void reserve_listed(size_t face_slots);
  void clear() { built_ = false; }
  bool built() const { return built_; }
  // Adds f's current box (f live). Rebuilds from scratch when stale entries pile up, and with
  // larger cells when the faces grew (the collapses of a coarsening pass).
  void insert(const mesh::SurfaceMesh& mesh, mesh::Face f);
  // The faces incident to v, after v moved or its fan changed.
  void insert_fan(const mesh::SurfaceMesh& mesh, mesh::Vertex v);
  // Appends to `out`, once each, the faces whose box as inserted touches the closed box
  // [lo, hi]; some may be deleted or have moved since (callers check). `budget` counts the cells
  // and entries looked at; returns false, with `out` incomplete, when it runs out.
  bool gather(const Point& lo, const Point& hi, std::vector<mesh::Face>& out, size_t& budget);
  // Calls visit(f, g) for each pair of distinct faces whose boxes touch, in one sweep over the
  // cells (cache-friendly, where a gather per face jumps around memory); right after build().
  // A pair is visited in the cell where its boxes' overlap starts (and again only when two of
  // its cells share a hash bucket). Stops when visit returns false; returns whether it ran to
  // the end. `budget` counts the pairs of entries looked at, and stops the sweep at zero: a fan
  // of thousands of needles in one cell has millions.
  template <class Visit>
  bool for_each_overlapping_pair(size_t& budget, Visit&& visit) const {
    return for_each_overlapping_pair(budget, [](mesh::Face, mesh::Face) { return true; }, visit);
  }
  // The same, visiting only the pairs `wanted` accepts: a cheap filter asked before the dedup,
  // which costs two floors and a hash per pair (the guard's sweep rejects nearly all pairs).
  template <class Wanted, class Visit>
  bool for_each_overlapping_pair(size_t& budget, Wanted&& wanted, Visit&& visit) const {
    return sweep(budget, [](const Entry& e) { return mesh::Face(e.face); }, wanted, visit);
  }
  // The same over a listed build's entries, naming each face by its key (position in the list):
  // a caller's per-face data is then as large as the list, not the mesh.
  template <class Wanted, class Visit>
  bool for_each_overlapping_listed_pair(size_t& budget, Wanted&& wanted, Visit&& visit) const {
    return sweep(budget, [](const Entry& e) { return e.next; }, wanted, visit);
  }
  bool overflowed() const;  // inserts since the last build

 private:
  static constexpr std::uint32_t kNone = 0xffffffffu;
  // The box is stored rounded outwards to floats: most candidates are rejected by the entry
  // alone, without reading the mesh.
  struct Entry {
    float lo[3], hi[3];
    // next: an overflow entry's next in its bucket (inserts after the build); a built entry's
    // key, its face's index into placed_ (the face slot, or in a listed build its list position).
    std::uint32_t face, next;
  };
  struct CellRange {
    std::int64_t lo[3], hi[3];
  };
  CellRange cells_of(const Point& lo, const Point& hi) const;
  template <class Key, class Wanted, class Visit>
  bool sweep(size_t& budget, Key&& key, Wanted&& wanted, Visit&& visit) const {
    const std::uint32_t buckets = mask_ + 1;
    for (std::uint32_t b = 0; b < buckets; ++b)
      for (std::uint32_t i = start_[b]; i < start_[b + 1]; ++i)
        for (std::uint32_t j = i + 1; j < start_[b + 1]; ++j) {
          if (budget == 0) return false;
          --budget;
          const Entry &e = entries_[i], &f = entries_[j];
          if (e.face == f.face || e.hi[0] < f.lo[0] || f.hi[0] < e.lo[0] || e.hi[1] < f.lo[1] || f.hi[1] < e.lo[1] ||
              e.hi[2] < f.lo[2] || f.hi[2] < e.lo[2])
            continue;
          if (!wanted(key(e), key(f))) continue;
          if (bucket(cell_of(std::max(e.lo[0], f.lo[0])), cell_of(std::max(e.lo[1], f.lo[1])),
                     cell_of(std::max(e.lo[2], f.lo[2]))) != b)
            continue;
          if (!visit(key(e), key(f))) return false;
        }
    return true;
  }
  // The cell index along an axis of a coordinate, as cells_of computes it (the pair sweep's
  // dedup needs one point's cell: half the floors of cells_of).
  // (Rounded down by hand: std::floor is a library call here, made six times per face and query.)
  std::int64_t cell_of(double x) const {
    const double y = x * inv_cell_;
    const auto i = static_cast<std::int64_t>(y);  // towards zero
    return static_cast<double>(i) > y ? i - 1 : i;
  }
  std::uint32_t bucket(std::int64_t i, std::int64_t j, std::int64_t k) const {
    const std::uint64_t h = static_cast<std::uint64_t>(i) * 73856093u ^ static_cast<std::uint64_t>(j) * 19349663u ^
                            static_cast<std::uint64_t>(k) * 83492791u;
    return static_cast<std::uint32_t>((h ^ (h >> 29)) & mask_);
  }
  Entry entry_of(const mesh::SurfaceMesh& mesh, mesh::Face f, CellRange* cells) const;
  Entry entry_of_box(std::uint32_t face, const Point& lo, const Point& hi, CellRange* cells) const;
  // The second half of a build, after box_lo_/box_hi_ hold the boxes (by key) of the faces
  // for_each_face visits (n_faces of them, all live, keys below n_keys) as visit(key, face).
  template <class ForEachFace>
  void fill(const mesh::SurfaceMesh& mesh, double cell_size, const Point& lo, const Point& hi, size_t n_faces,
            size_t n_keys, ForEachFace&& for_each_face);
  template <class Visit>
  void for_each_bucket(const CellRange& r, Visit&& visit) const {
    for (std::int64_t i = r.lo[0]; i <= r.hi[0]; ++i)
      for (std::int64_t j = r.lo[1]; j <= r.hi[1]; ++j)
        for (std::int64_t k = r.lo[2]; k <= r.hi[2]; ++k) visit(bucket(i, j, k));
  }
  static size_t cell_count(const CellRange& r) {
    return static_cast<size_t>(r.hi[0] - r.lo[0] + 1) * static_cast<size_t>(r.hi[1] - r.lo[1] + 1) *
           static_cast<size_t>(r.hi[2] - r.lo[2] + 1);
  }

  bool built_ = false;
  bool listed_ = false;  // built over a list of faces: never rebuilt by insert()
  double cell_size_ = 1, inv_cell_ = 1;
  std::uint32_t mask_ = 0;
  size_t rebuild_at_ = 0;  // overflow entries beyond which insert() rebuilds
  // Overflow entries the queries walked since the last build: inserts pile up where the remesher works, and a
  // query there walks those buckets' lists; insert() rebuilds once the walking has cost a few builds.
  size_t overflow_walked_ = 0;
  // Cells a new box spans along its longest axis, summed over recent inserts (see insert()).
  size_t span_sum_ = 0, inserts_ = 0;
  // The build's entries, bucket by bucket (bucket b: entries_[start_[b]] to entries_[start_[b + 1]]):
  // a query reads each bucket's entries in one run. Later inserts go to per-bucket lists.
  std::vector<std::uint32_t> start_;
  std::vector<Entry> entries_;
  std::vector<std::uint32_t> overflow_head_;  // per bucket: its last inserted entry in overflow_
  std::vector<Entry> overflow_;
  // Where build() put each face's entries, for updates in place: most edits (a flip, a collapse's
  // fan, a relaxed vertex) leave a face's box in the same cells. The overflow lists, the other
  // way, cost a cache miss per entry to every query that walks them (half a remesh's queries'
  // time before). count 0: none, or more cells than kMaxPlaced.
  static constexpr int kMaxPlaced = 8;
  struct Placed {
    std::uint32_t count = 0;
    std::uint32_t at[kMaxPlaced];
  };
  std::vector<Placed> placed_;  // per key
  Placed* placed_of(mesh::Face f);  // nullptr: not placed by the current build
  std::vector<Point> box_lo_, box_hi_;  // build()'s scratch: per key
  std::vector<Entry> box_entry_;        // build()'s scratch: per key
  std::vector<CellRange> box_cells_;    // build()'s scratch: per key
  // A listed build's faces by position, and per face slot its position (current only where
  // listed_faces_ agrees: never cleared).
  std::vector<std::uint32_t> listed_faces_, listed_at_;
  std::vector<std::uint32_t> seen_;  // per face slot: == run_ when gathered by the current query
  std::uint32_t run_ = 0;
};

}  // namespace adasculpt::geometry
