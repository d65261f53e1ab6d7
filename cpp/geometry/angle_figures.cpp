#include "geometry/angle_figures.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace adasculpt::geometry {

namespace {
constexpr double kFixed = 4294967296.0;  // 2^32: 60 degrees x 10^7 faces still fits an int64
std::int64_t fixed(double deg) { return std::int64_t(std::llround(deg * kFixed)); }
}  // namespace

void AngleFigures::mark_face(mesh::Face f) {
  if (!built_ || !f.is_valid() || f.idx >= mark_.size() || mark_[f.idx]) return;  // later slots: sync
  mark_[f.idx] = 1;
  dirty_.push_back(f.idx);
}

void AngleFigures::mark_vertex(const mesh::SurfaceMesh& m, mesh::Vertex v) {
  if (!built_ || !v.is_valid() || v.idx >= m.vertices_size() || m.is_deleted(v)) return;
  for (mesh::Face f : m.faces(v)) mark_face(f);
}

void AngleFigures::resize(size_t slots) {
  if (slots <= min_deg_.size()) return;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  min_deg_.resize(slots, nan);
  max_deg_.resize(slots, nan);
  mark_.resize(slots, 0);
  const size_t blocks = (slots + kBlock - 1) / kBlock;
  block_min_.resize(blocks, std::numeric_limits<double>::infinity());
  block_max_.resize(blocks, -std::numeric_limits<double>::infinity());
  block_mark_.resize(blocks, 0);
}

void AngleFigures::set_face(const mesh::SurfaceMesh& m, std::uint32_t slot) {
  ++last_work_;
  double& lo = min_deg_[slot];
  if (!std::isnan(lo)) {  // take back the slot's old share
    sum_min_fixed_ -= fixed(lo);
    --live_;
    lt30_ -= lo < 30;
    lt10_ -= lo < 10;
  }
  lo = max_deg_[slot] = std::numeric_limits<double>::quiet_NaN();
  if (slot < m.faces_size() && !m.is_deleted(mesh::Face(slot))) {
    mesh::Vertex v[3];
    m.face_vertices(mesh::Face(slot), v);
    const TriangleAngles t = triangle_angle_extremes(m.position(v[0]), m.position(v[1]), m.position(v[2]));
    lo = t.min_deg;
    max_deg_[slot] = t.max_deg;
    sum_min_fixed_ += fixed(lo);
    ++live_;
    lt30_ += lo < 30;
    lt10_ += lo < 10;
  }
  const std::uint32_t b = slot / kBlock;
  if (!block_mark_[b]) {
    block_mark_[b] = 1;
    dirty_blocks_.push_back(b);
  }
}

void AngleFigures::fit_block(std::uint32_t b) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  const size_t end = std::min(min_deg_.size(), size_t(b + 1) * kBlock);
  for (size_t i = size_t(b) * kBlock; i < end; ++i) {
    if (std::isnan(min_deg_[i])) continue;
    lo = std::min(lo, min_deg_[i]);
    hi = std::max(hi, max_deg_[i]);
  }
  block_min_[b] = lo;
  block_max_[b] = hi;
}

void AngleFigures::sync(const mesh::SurfaceMesh& m) {
  last_work_ = 0;
  const size_t n = m.faces_size();
  if (!built_) {
    *this = AngleFigures{};
    resize(n);
    for (std::uint32_t f = 0; f < n; ++f) set_face(m, f);
    synced_faces_ = n;
    built_ = true;
  }
  resize(n);
  // Slots added at the end (new faces) or cut off (an undo truncated the arrays) since the last sync.
  for (size_t f = std::min(n, synced_faces_); f < std::max(n, synced_faces_); ++f) set_face(m, std::uint32_t(f));
  synced_faces_ = n;
  for (std::uint32_t f : dirty_) {
    mark_[f] = 0;
    set_face(m, f);
  }
  dirty_.clear();
  for (std::uint32_t b : dirty_blocks_) {
    block_mark_[b] = 0;
    fit_block(b);
  }
  dirty_blocks_.clear();
}

void AngleFigures::fill(QualityReport& r) const {
  r.faces = live_;
  if (live_ == 0) return;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (size_t b = 0; b < block_min_.size(); ++b) {
    lo = std::min(lo, block_min_[b]);
    hi = std::max(hi, block_max_[b]);
  }
  r.min_angle_deg = lo;
  r.max_angle_deg = hi;
  r.mean_min_angle_deg = double(sum_min_fixed_) / kFixed / double(live_);
  r.pct_min_angle_lt_30 = 100.0 * double(lt30_) / double(live_);
  r.pct_min_angle_lt_10 = 100.0 * double(lt10_) / double(live_);
}

}  // namespace adasculpt::geometry
