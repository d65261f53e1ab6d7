#include "geometry/face_grid.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <glm/common.hpp>

#include "mesh/scratch.h"

namespace adasculpt::geometry {

namespace {
// Buckets per face: hash collisions of different cells only add candidates.
constexpr size_t kBucketsPerFace = 2;
// Stale entries allowed, in multiples of a fresh build's, before insert() rebuilds.
constexpr double kStaleFactor = 2;
// No more cells than this along an axis of the mesh's box: a coarse mesh with a few tiny faces
// would otherwise put its large faces into millions of cells.
constexpr double kMaxCellsPerAxis = 1024;
// Overflow entries walked by queries, in multiples of a fresh build's entries, before insert() rebuilds (a build
// reads each entry about twice). On a CAD part refined along its creases the lists there grew to hundreds of
// entries a query, most of them stale: the walks were a quarter of the remesh.
constexpr size_t kWalkFactor = 4;
// See insert(): inserts per measurement of the new faces' spans, and the mean span allowed.
constexpr size_t kSpanWindow = 256;
constexpr size_t kMaxMeanSpan = 3;
}  // namespace

FaceGrid::CellRange FaceGrid::cells_of(const Point& lo, const Point& hi) const {
  CellRange r;
  for (int a = 0; a < 3; ++a) {
    r.lo[a] = cell_of(lo[a]);
    r.hi[a] = cell_of(hi[a]);
  }
  return r;
}

namespace {
// The next float below (above) a finite f, by its bits: std::nextafter is a library call, and
// a build rounds six coordinates per face.
float float_step_down(float f) {
  if (f == 0) return -std::numeric_limits<float>::denorm_min();
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  bits = f > 0 ? bits - 1 : bits + 1;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}
// x rounded to a float no larger (no smaller): boxes stored as floats still contain the face.
float float_below(double x) {
  const float f = static_cast<float>(x);
  return static_cast<double>(f) > x ? float_step_down(f) : f;
}
float float_above(double x) {
  const float f = static_cast<float>(x);
  return static_cast<double>(f) < x ? -float_step_down(-f) : f;
}
}  // namespace

FaceGrid::Entry FaceGrid::entry_of(const mesh::SurfaceMesh& mesh, mesh::Face f, CellRange* cells) const {
  mesh::Vertex v[3];
  mesh.face_vertices(f, v);
  const Point &a = mesh.position(v[0]), &b = mesh.position(v[1]), &c = mesh.position(v[2]);
  return entry_of_box(f.idx, glm::min(a, glm::min(b, c)), glm::max(a, glm::max(b, c)), cells);
}

FaceGrid::Entry FaceGrid::entry_of_box(std::uint32_t face, const Point& lo, const Point& hi, CellRange* cells) const {
  Entry entry;
  entry.face = face;
  entry.next = kNone;
  for (int k = 0; k < 3; ++k) {
    entry.lo[k] = float_below(lo[k]);
    entry.hi[k] = float_above(hi[k]);
  }
  // The cells of the stored box: every point of it, such as the corner where two boxes start to
  // overlap (for_each_overlapping_pair), lies in a cell that lists the face.
  *cells = cells_of(Point(entry.lo[0], entry.lo[1], entry.lo[2]), Point(entry.hi[0], entry.hi[1], entry.hi[2]));
  return entry;
}

void FaceGrid::build(const mesh::SurfaceMesh& mesh, double cell_size) {
  Point lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (mesh::Vertex v : mesh.vertices()) {
    lo = glm::min(lo, mesh.position(v));
    hi = glm::max(hi, mesh.position(v));
  }
  // The face boxes from one scan of the halfedges in memory order: following each face's
  // halfedges instead was the slow part of a build (a cache miss or more per corner on a
  // remeshed mesh, whose elements are far from memory order). Read again by fill().
  const size_t n_slots = mesh.faces_size();
  box_lo_.assign(n_slots, Point(std::numeric_limits<double>::infinity()));
  box_hi_.assign(n_slots, Point(-std::numeric_limits<double>::infinity()));
  const auto* hc = mesh.halfedge_connectivity_data();
  const std::uint8_t* edel = mesh.edge_deleted_data();
  const Point* pos = mesh.positions().data();
  const size_t n_halfedges = mesh.halfedges_size();
  for (size_t h = 0; h < n_halfedges; ++h) {
    const mesh::Face f = hc[h].face;
    if (edel[h >> 1] || !f.is_valid()) continue;
    const Point& p = pos[hc[h].to.idx];
    box_lo_[f.idx] = glm::min(box_lo_[f.idx], p);
    box_hi_[f.idx] = glm::max(box_hi_[f.idx], p);
  }
  const std::uint8_t* fdel = mesh.face_deleted_data();
  listed_ = false;
  fill(mesh, cell_size, lo, hi, mesh.n_faces(), n_slots, [&](auto&& visit) {
    for (size_t f = 0; f < n_slots; ++f)
      if (!fdel[f]) visit(f, static_cast<std::uint32_t>(f));
  });
}

void FaceGrid::build(const mesh::SurfaceMesh& mesh, double cell_size, const std::vector<mesh::Face>& faces) {
  Point lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  const size_t n = faces.size();
  mesh::resize_scratch(box_lo_, n);
  mesh::resize_scratch(box_hi_, n);
  mesh::resize_scratch(listed_faces_, n);
  mesh::resize_scratch(listed_at_, mesh.faces_size());
  for (size_t i = 0; i < n; ++i) {
    const mesh::Face f = faces[i];
    mesh::Vertex v[3];
    mesh.face_vertices(f, v);
    const Point &a = mesh.position(v[0]), &b = mesh.position(v[1]), &c = mesh.position(v[2]);
    box_lo_[i] = glm::min(a, glm::min(b, c));
    box_hi_[i] = glm::max(a, glm::max(b, c));
    lo = glm::min(lo, box_lo_[i]);
    hi = glm::max(hi, box_hi_[i]);
    listed_faces_[i] = f.idx;
    listed_at_[f.idx] = static_cast<std::uint32_t>(i);
  }
  listed_ = true;
  fill(mesh, cell_size, lo, hi, n, n, [&](auto&& visit) {
    for (size_t i = 0; i < n; ++i) visit(i, faces[i].idx);
  });
}

template <class ForEachFace>
void FaceGrid::fill(const mesh::SurfaceMesh& mesh, double cell_size, const Point& lo, const Point& hi, size_t n_faces,
                    size_t n_keys, ForEachFace&& for_each_face) {
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 0.0});
  cell_size_ = std::max(cell_size, extent / kMaxCellsPerAxis);
  if (!(cell_size_ > 0)) cell_size_ = 1;
  inv_cell_ = 1.0 / cell_size_;
  size_t buckets = 1024;
  while (buckets < kBucketsPerFace * n_faces) buckets *= 2;
  mask_ = static_cast<std::uint32_t>(buckets - 1);
  // Counting sort by bucket: count, offsets, then fill (start_[b + 1] counts down to start_[b]).
  start_.assign(buckets + 1, 0u);
  // Each face's entry and cells once, kept for the fill pass: computing them (float rounding,
  // floors) was a fifth of a build.
  mesh::resize_scratch(box_entry_, n_keys);
  mesh::resize_scratch(box_cells_, n_keys);
  for_each_face([&](size_t key, std::uint32_t f) {
    box_entry_[key] = entry_of_box(f, box_lo_[key], box_hi_[key], &box_cells_[key]);
    box_entry_[key].next = static_cast<std::uint32_t>(key);
    for_each_bucket(box_cells_[key], [&](std::uint32_t b) { ++start_[b + 1]; });
  });
  for (size_t b = 0; b < buckets; ++b) start_[b + 1] += start_[b];
  entries_.resize(start_[buckets]);
  mesh::resize_scratch(placed_, n_keys);
  for_each_face([&](size_t key, std::uint32_t) {
    const CellRange& r = box_cells_[key];
    const Entry& entry = box_entry_[key];
    Placed& placed = placed_[key];
    placed.count = 0;
    bool all = true;
    for_each_bucket(r, [&](std::uint32_t b) {
      const std::uint32_t at = --start_[b + 1];
      entries_[at] = entry;
      if (placed.count < kMaxPlaced)
        placed.at[placed.count++] = at;
      else
        all = false;
    });
    if (!all) placed.count = 0;
  });
  // start_[b + 1] now holds the start of bucket b: move the offsets down by one bucket.
  for (size_t b = 0; b < buckets; ++b) start_[b] = start_[b + 1];
  start_[buckets] = static_cast<std::uint32_t>(entries_.size());
  overflow_head_.assign(buckets, kNone);
  overflow_.clear();
  if (seen_.size() < mesh.faces_size()) seen_.resize(mesh.faces_size(), 0u);
  rebuild_at_ = static_cast<size_t>(kStaleFactor * static_cast<double>(std::max<size_t>(entries_.size(), 1024)));
  span_sum_ = inserts_ = 0;
  overflow_walked_ = 0;
  built_ = true;
}

FaceGrid::Placed* FaceGrid::placed_of(mesh::Face f) {
  if (!listed_) return f.idx < placed_.size() ? &placed_[f.idx] : nullptr;
  if (f.idx >= listed_at_.size()) return nullptr;
  const std::uint32_t at = listed_at_[f.idx];  // (stale unless the list holds f there)
  return at < listed_faces_.size() && listed_faces_[at] == f.idx ? &placed_[at] : nullptr;
}

void FaceGrid::insert(const mesh::SurfaceMesh& mesh, mesh::Face f) {
  if (!built_) return;
  if ((overflow_.size() > rebuild_at_ || overflow_walked_ > kWalkFactor * entries_.size()) && !listed_) {
    build(mesh, cell_size_);
    return;
  }
  if (f.idx >= seen_.size()) seen_.resize(mesh.faces_size(), 0u);
  CellRange r;
  Entry entry = entry_of(mesh, f, &r);
  Placed* placed = placed_of(f);
  if (placed && placed->count > 0) {
    const Entry& old = entries_[placed->at[0]];
    const CellRange was = cells_of(Point(old.lo[0], old.lo[1], old.lo[2]), Point(old.hi[0], old.hi[1], old.hi[2]));
    if (std::equal(r.lo, r.lo + 3, was.lo) && std::equal(r.hi, r.hi + 3, was.hi)) {
      entry.next = old.next;  // (the key of a built entry)
      for (std::uint32_t k = 0; k < placed->count; ++k) entries_[placed->at[k]] = entry;
      return;
    }
    // From now on in the overflow lists. A listed grid's sweep must not meet the old box: its
    // entries are emptied. (The whole-mesh grid leaves them, stale, as its queries always did.)
    if (listed_)
      for (std::uint32_t k = 0; k < placed->count; ++k) {
        Entry& stale = entries_[placed->at[k]];
        std::fill(stale.lo, stale.lo + 3, std::numeric_limits<float>::infinity());
        std::fill(stale.hi, stale.hi + 3, -std::numeric_limits<float>::infinity());
      }
    placed->count = 0;
  }
  for_each_bucket(r, [&](std::uint32_t b) {
    entry.next = overflow_head_[b];
    overflow_.push_back(entry);
    overflow_head_[b] = static_cast<std::uint32_t>(overflow_.size() - 1);
  });
  if (listed_) return;  // never rebuilt (a rebuild would list the whole mesh)
  span_sum_ += static_cast<size_t>(std::max({r.hi[0] - r.lo[0], r.hi[1] - r.lo[1], r.hi[2] - r.lo[2]}) + 1);
  // Faces that span many cells cost an entry per cell and make every query near them visit as
  // many: once the new faces average more than kMaxMeanSpan cells across, the cells double.
  if (++inserts_ >= kSpanWindow && span_sum_ > kMaxMeanSpan * inserts_) build(mesh, 2 * cell_size_);
  if (inserts_ >= kSpanWindow) span_sum_ = inserts_ = 0;
}

void FaceGrid::insert_fan(const mesh::SurfaceMesh& mesh, mesh::Vertex v) {
  if (!built_) return;
  for (mesh::Face f : mesh.faces(v)) insert(mesh, f);
}


bool FaceGrid::gather(const Point& lo, const Point& hi, std::vector<mesh::Face>& out, size_t& budget) {
  const CellRange r = cells_of(lo, hi);
  const size_t cells = cell_count(r);
  if (cells > budget) {
    budget = 0;
    return false;
  }
  budget -= cells;
  if (++run_ == 0) {
    std::fill(seen_.begin(), seen_.end(), 0u);
    run_ = 1;
  }
  bool within = true;
  auto take = [&](const Entry& en) {
    if (budget == 0) {
      within = false;
      return;
    }
    --budget;
    // The box first: a stale entry that misses must not hide the face's current one.
    if (en.hi[0] < lo.x || en.lo[0] > hi.x || en.hi[1] < lo.y || en.lo[1] > hi.y || en.hi[2] < lo.z || en.lo[2] > hi.z)
      return;
    if (seen_[en.face] == run_) return;
    seen_[en.face] = run_;
    out.push_back(mesh::Face(en.face));
  };
  for_each_bucket(r, [&](std::uint32_t b) {
    for (std::uint32_t e = start_[b]; e < start_[b + 1] && within; ++e) take(entries_[e]);
    for (std::uint32_t e = overflow_head_[b]; e != kNone && within; e = overflow_[e].next) {
      ++overflow_walked_;
      take(overflow_[e]);
    }
  });
  return within;
}

bool FaceGrid::overflowed() const { return !overflow_.empty(); }

void FaceGrid::reserve_listed(size_t face_slots) {
  mesh::resize_scratch(listed_at_, face_slots);
  if (seen_.size() < face_slots) seen_.resize(face_slots, 0u);
}

}  // namespace adasculpt::geometry
