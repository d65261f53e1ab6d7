#include "geometry/face_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>

namespace adasculpt::geometry {

namespace {
// Buckets per face: hash collisions of different cells only add candidates.
constexpr size_t kBucketsPerFace = 2;
// Stale entries allowed, in multiples of a fresh build's, before insert() rebuilds.
constexpr double kStaleFactor = 2;
// No more cells than this along an axis of the mesh's box: a coarse mesh with a few tiny faces
// would otherwise put its large faces into millions of cells.
constexpr double kMaxCellsPerAxis = 1024;
// See insert(): inserts per measurement of the new faces' spans, and the mean span allowed.
constexpr size_t kSpanWindow = 256;
constexpr size_t kMaxMeanSpan = 3;
}  // namespace

FaceGrid::CellRange FaceGrid::cells_of(const Point& lo, const Point& hi) const {
  CellRange r;
  for (int a = 0; a < 3; ++a) {
    r.lo[a] = static_cast<std::int64_t>(std::floor(lo[a] * inv_cell_));
    r.hi[a] = static_cast<std::int64_t>(std::floor(hi[a] * inv_cell_));
  }
  return r;
}

namespace {
// x rounded to a float no larger (no smaller): boxes stored as floats still contain the face.
float float_below(double x) {
  const float f = static_cast<float>(x);
  return static_cast<double>(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
float float_above(double x) {
  const float f = static_cast<float>(x);
  return static_cast<double>(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}
}  // namespace

FaceGrid::Entry FaceGrid::entry_of(const mesh::SurfaceMesh& mesh, mesh::Face f, CellRange* cells) const {
  mesh::Vertex v[3];
  mesh.face_vertices(f, v);
  const Point &a = mesh.position(v[0]), &b = mesh.position(v[1]), &c = mesh.position(v[2]);
  const Point lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
  Entry entry;
  entry.face = f.idx;
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
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 0.0});
  cell_size_ = std::max(cell_size, extent / kMaxCellsPerAxis);
  if (!(cell_size_ > 0)) cell_size_ = 1;
  inv_cell_ = 1.0 / cell_size_;
  size_t buckets = 1024;
  while (buckets < kBucketsPerFace * mesh.n_faces()) buckets *= 2;
  mask_ = static_cast<std::uint32_t>(buckets - 1);
  // Counting sort by bucket: count, offsets, then fill (start_[b + 1] counts down to start_[b]).
  // (The faces' entries and cells are kept between the two passes: reading a face's corners
  // is the slow part, a cache miss or more each on a remeshed mesh.)
  start_.assign(buckets + 1, 0u);
  staged_.clear();
  for (mesh::Face f : mesh.faces()) {
    CellRange r;
    const Entry entry = entry_of(mesh, f, &r);
    staged_.push_back({entry, r});
    for_each_bucket(r, [&](std::uint32_t b) { ++start_[b + 1]; });
  }
  for (size_t b = 0; b < buckets; ++b) start_[b + 1] += start_[b];
  entries_.resize(start_[buckets]);
  for (const Staged& s : staged_)
    for_each_bucket(s.cells, [&](std::uint32_t b) { entries_[--start_[b + 1]] = s.entry; });
  // start_[b + 1] now holds the start of bucket b: move the offsets down by one bucket.
  for (size_t b = 0; b < buckets; ++b) start_[b] = start_[b + 1];
  start_[buckets] = static_cast<std::uint32_t>(entries_.size());
  overflow_head_.assign(buckets, kNone);
  overflow_.clear();
  if (seen_.size() < mesh.faces_size()) seen_.resize(mesh.faces_size(), 0u);
  rebuild_at_ = static_cast<size_t>(kStaleFactor * static_cast<double>(std::max<size_t>(entries_.size(), 1024)));
  span_sum_ = inserts_ = 0;
  built_ = true;
}

void FaceGrid::insert(const mesh::SurfaceMesh& mesh, mesh::Face f) {
  if (!built_) return;
  if (overflow_.size() > rebuild_at_) {
    build(mesh, cell_size_);
    return;
  }
  if (f.idx >= seen_.size()) seen_.resize(mesh.faces_size(), 0u);
  CellRange r;
  Entry entry = entry_of(mesh, f, &r);
  for_each_bucket(r, [&](std::uint32_t b) {
    entry.next = overflow_head_[b];
    overflow_.push_back(entry);
    overflow_head_[b] = static_cast<std::uint32_t>(overflow_.size() - 1);
  });
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


void FaceGrid::gather(const Point& lo, const Point& hi, std::vector<mesh::Face>& out) {
  if (++run_ == 0) {
    std::fill(seen_.begin(), seen_.end(), 0u);
    run_ = 1;
  }
  auto take = [&](const Entry& en) {
    // The box first: a stale entry that misses must not hide the face's current one.
    if (en.hi[0] < lo.x || en.lo[0] > hi.x || en.hi[1] < lo.y || en.lo[1] > hi.y || en.hi[2] < lo.z || en.lo[2] > hi.z)
      return;
    if (seen_[en.face] == run_) return;
    seen_[en.face] = run_;
    out.push_back(mesh::Face(en.face));
  };
  for_each_bucket(cells_of(lo, hi), [&](std::uint32_t b) {
    for (std::uint32_t e = start_[b]; e < start_[b + 1]; ++e) take(entries_[e]);
    for (std::uint32_t e = overflow_head_[b]; e != kNone; e = overflow_[e].next) take(overflow_[e]);
  });
}

bool FaceGrid::overflowed() const { return !overflow_.empty(); }

}  // namespace adasculpt::geometry
