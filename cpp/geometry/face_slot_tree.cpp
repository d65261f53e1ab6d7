#include "geometry/face_slot_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "geometry/aabb_tree.h"
#include "geometry/triangle.h"

namespace adasculpt::geometry {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// 10-bit cells interleaved into a 30-bit Morton code.
std::uint32_t spread10(std::uint32_t v) {
  v = (v | (v << 16)) & 0x030000FFu;
  v = (v | (v << 8)) & 0x0300F00Fu;
  v = (v | (v << 4)) & 0x030C30C3u;
  return (v | (v << 2)) & 0x09249249u;
}

bool live(const mesh::SurfaceMesh& m, std::uint32_t slot) {
  return slot < m.faces_size() && !m.is_deleted(mesh::Face(slot));
}

void slot_corners(const mesh::SurfaceMesh& m, std::uint32_t slot, Point out[3]) {
  mesh::Vertex v[3];
  m.face_vertices(mesh::Face(slot), v);
  for (int i = 0; i < 3; ++i) out[i] = m.position(v[i]);
}

// The lower slot wins a tie, as in a scan of the slots in order.
bool better(double key, std::uint32_t slot, double best, mesh::Face best_face) {
  return key < best || (key == best && best_face.is_valid() && slot < best_face.idx);
}

}  // namespace

void FaceSlotTree::mark_leaf(std::uint32_t leaf) {
  Level& l = levels_[0];
  if (leaf >= l.mark.size() || l.mark[leaf]) return;
  l.mark[leaf] = 1;
  l.dirty.push_back(leaf);
}

void FaceSlotTree::mark_face(mesh::Face f) {
  if (!built_ || !f.is_valid()) return;
  if (f.idx < rank_.size()) mark_leaf(rank_[f.idx] / kFan);  // later slots are fitted when taken in
}

void FaceSlotTree::mark_vertex(const mesh::SurfaceMesh& m, mesh::Vertex v) {
  if (!built_ || !v.is_valid() || v.idx >= m.vertices_size() || m.is_deleted(v)) return;
  for (mesh::Face f : m.faces(v)) mark_face(f);
}

namespace {
size_t with_room(size_t n) { return n + n / 8 + 16; }
}  // namespace

void FaceSlotTree::build(const mesh::SurfaceMesh& m) {
  const std::uint32_t n = std::uint32_t(m.faces_size());
  // One read of every triangle: its centroid (NaN for a deleted slot), and their box.
  std::vector<Point> mid(n, Point(std::numeric_limits<double>::quiet_NaN()));
  Point lo(kInf), hi(-kInf);
  for (std::uint32_t f = 0; f < n; ++f) {
    if (!live(m, f)) continue;
    Point c[3];
    slot_corners(m, f, c);
    mid[f] = (c[0] + c[1] + c[2]) / 3.0;
    lo = glm::min(lo, mid[f]);
    hi = glm::max(hi, mid[f]);
  }
  const double span = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-300});
  std::vector<std::uint64_t> keys(n);
  for (std::uint32_t f = 0; f < n; ++f) {
    std::uint64_t code = 0xFFFFFFFFull;  // deleted slots last
    if (!std::isnan(mid[f].x)) {
      std::uint32_t cell[3];
      for (int k = 0; k < 3; ++k)
        cell[k] = std::uint32_t(std::clamp((mid[f][k] - lo[k]) / span * 1024.0, 0.0, 1023.0));
      code = spread10(cell[0]) | (spread10(cell[1]) << 1) | (spread10(cell[2]) << 2);
    }
    keys[f] = (code << 32) | f;
  }
  std::sort(keys.begin(), keys.end());
  // Room for the slots the next strokes add (as SurfaceMesh::reserve_room_for_edits): grown in a
  // stroke, the reallocations of these and of the levels below cost the first stroke after a load
  // of 1.1M triangles ~15 ms (copies and first-touch page faults; issue 18).
  order_.reserve(with_room(n));
  rank_.reserve(with_room(n));
  order_.resize(n);
  rank_.resize(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    order_[i] = std::uint32_t(keys[i] & 0xFFFFFFFFull);
    rank_[order_[i]] = i;
  }
  levels_.clear();
  synced_faces_ = n;
  built_ = true;
  resize_levels();  // every box new, so every box marked
}

// Levels for order_.size() slots; boxes that are new are marked for fitting.
void FaceSlotTree::resize_levels() {
  size_t n = std::max<size_t>(1, (order_.size() + kFan - 1) / kFan);
  for (size_t k = 0;; ++k) {
    if (k == levels_.size()) levels_.emplace_back();
    Level& l = levels_[k];
    const size_t had = l.boxes.size();
    if (n > had) {
      if (n > l.boxes.capacity()) {
        l.boxes.reserve(with_room(n));
        l.mark.reserve(with_room(n));
      }
      l.boxes.resize(n, Box{Point(kInf), Point(-kInf)});
      l.mark.resize(n, 0);
      for (size_t b = had; b < n; ++b) {
        l.mark[b] = 1;
        l.dirty.push_back(std::uint32_t(b));
      }
    }
    if (n == 1) {
      levels_.resize(k + 1);
      return;
    }
    n = (n + kFan - 1) / kFan;
  }
}

// Slots added at the end join in slot order; slots added or cut off since the last sync are refitted.
void FaceSlotTree::take_new_slots(const mesh::SurfaceMesh& m) {
  const size_t n = m.faces_size();
  if (n > order_.size()) {
    for (size_t f = order_.size(); f < n; ++f) {
      rank_.push_back(std::uint32_t(order_.size()));
      order_.push_back(std::uint32_t(f));
    }
    resize_levels();
  }
  for (size_t f = std::min(n, synced_faces_); f < std::max(n, synced_faces_); ++f) mark_leaf(rank_[f] / kFan);
  synced_faces_ = n;
}

void FaceSlotTree::fit_leaf(const mesh::SurfaceMesh& m, std::uint32_t leaf) {
  Point lo(kInf), hi(-kInf);
  const size_t end = std::min<size_t>(order_.size(), size_t(leaf + 1) * kFan);
  for (size_t i = size_t(leaf) * kFan; i < end; ++i) {
    if (!live(m, order_[i])) continue;
    Point c[3];
    slot_corners(m, order_[i], c);
    for (const Point& p : c) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  }
  if (lo.x <= hi.x) {
    // Padding keeps the box conservative against the rounding of the queries' arithmetic.
    const Vec3 big = glm::max(glm::abs(lo), glm::abs(hi));
    const double pad = 1e-9 * std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, big.x, big.y, big.z}) + 1e-300;
    lo -= Vec3(pad);
    hi += Vec3(pad);
  }
  levels_[0].boxes[leaf] = {lo, hi};
}

void FaceSlotTree::fit_parent(size_t level, std::uint32_t b) {
  const std::vector<Box>& below = levels_[level - 1].boxes;
  Box box{Point(kInf), Point(-kInf)};
  const size_t end = std::min<size_t>(below.size(), size_t(b + 1) * kFan);
  for (size_t c = size_t(b) * kFan; c < end; ++c) {
    box.lo = glm::min(box.lo, below[c].lo);
    box.hi = glm::max(box.hi, below[c].hi);
  }
  levels_[level].boxes[b] = box;
}

void FaceSlotTree::sync(const mesh::SurfaceMesh& m) {
  last_refit_ = 0;
  if (!built_) build(m);
  take_new_slots(m);
  for (size_t k = 0; k < levels_.size(); ++k) {
    Level& l = levels_[k];
    if (k == 0) last_refit_ = l.dirty.size();
    for (std::uint32_t b : l.dirty) {
      l.mark[b] = 0;
      if (k == 0)
        fit_leaf(m, b);
      else
        fit_parent(k, b);
      if (k + 1 < levels_.size()) {
        Level& up = levels_[k + 1];
        const std::uint32_t parent = b / kFan;
        if (!up.mark[parent]) {
          up.mark[parent] = 1;
          up.dirty.push_back(parent);
        }
      }
    }
    l.dirty.clear();
  }
}

template <class Key, class Test>
void FaceSlotTree::search(const mesh::SurfaceMesh& m, size_t level, std::uint32_t first, std::uint32_t end,
                          const Key& key, const Test& test, const double& best) const {
  const std::vector<Box>& boxes = levels_[level].boxes;
  double keys[kFan];
  std::uint32_t child[kFan];
  int n = 0;
  for (std::uint32_t c = first; c < end; ++c) {  // at most kFan (the top level holds one box)
    const double k = key(boxes[c]);
    if (k < 0 || k > best) continue;
    int j = n++;
    for (; j > 0 && keys[j - 1] > k; --j) {
      keys[j] = keys[j - 1];
      child[j] = child[j - 1];
    }
    keys[j] = k;
    child[j] = c;
  }
  for (int i = 0; i < n; ++i) {
    if (keys[i] > best) break;  // a tie is still searched: the lower slot may win it
    const std::uint32_t c = child[i];
    if (level == 0) {
      const size_t stop = std::min<size_t>(order_.size(), size_t(c + 1) * kFan);
      for (size_t s = size_t(c) * kFan; s < stop; ++s)
        if (live(m, order_[s])) test(order_[s]);
    } else {
      const std::uint32_t below = std::uint32_t(levels_[level - 1].boxes.size());
      search(m, level - 1, c * kFan, std::min(below, (c + 1) * kFan), key, test, best);
    }
  }
}

FaceSlotTree::Hit FaceSlotTree::intersect_ray(const mesh::SurfaceMesh& m, const Point& origin,
                                              const Vec3& dir) const {
  Hit best;
  best.t = kInf;
  if (!built_ || levels_.empty()) return best;
  bool parallel[3];
  Vec3 inv;
  for (int k = 0; k < 3; ++k) {
    parallel[k] = dir[k] == 0.0;
    inv[k] = parallel[k] ? 0.0 : 1.0 / dir[k];
  }
  auto key = [&](const Box& n) {
    double t0 = 0.0, t1 = kInf;
    if (!(n.lo.x <= n.hi.x)) return -1.0;
    for (int k = 0; k < 3; ++k) {
      if (parallel[k]) {
        if (origin[k] < n.lo[k] || origin[k] > n.hi[k]) return -1.0;
        continue;
      }
      double a = (n.lo[k] - origin[k]) * inv[k], b = (n.hi[k] - origin[k]) * inv[k];
      if (a > b) std::swap(a, b);
      t0 = std::max(t0, a);
      t1 = std::min(t1, b);
    }
    return t0 <= t1 ? t0 : -1.0;
  };
  auto test = [&](std::uint32_t slot) {
    Point c[3];
    slot_corners(m, slot, c);
    double t, u, v;
    if (!ray_triangle(origin, dir, c[0], c[1], c[2], &t, &u, &v) || !better(t, slot, best.t, best.face)) return;
    best.t = t;
    best.face = mesh::Face(slot);
    best.bary[0] = 1.0 - u - v;
    best.bary[1] = u;
    best.bary[2] = v;
    best.point = c[0] + u * (c[1] - c[0]) + v * (c[2] - c[0]);  // on the triangle, as TriangleTree's
  };
  search(m, levels_.size() - 1, 0, 1, key, test, best.t);
  return best;
}

FaceSlotTree::Hit FaceSlotTree::closest_point(const mesh::SurfaceMesh& m, const Point& q) const {
  Hit best;
  best.distance2 = kInf;
  if (!built_ || levels_.empty()) return best;
  auto key = [&](const Box& n) {
    if (!(n.lo.x <= n.hi.x)) return -1.0;
    const Vec3 d = glm::max(glm::max(n.lo - q, q - n.hi), Vec3(0.0));
    return glm::dot(d, d);
  };
  auto test = [&](std::uint32_t slot) {
    Point c[3];
    slot_corners(m, slot, c);
    double bary[3];
    const Point p = closest_point_on_triangle(q, c[0], c[1], c[2], bary);
    const double d2 = glm::dot(p - q, p - q);
    if (!better(d2, slot, best.distance2, best.face)) return;
    best.distance2 = d2;
    best.face = mesh::Face(slot);
    best.point = p;
    std::copy(bary, bary + 3, best.bary);
  };
  search(m, levels_.size() - 1, 0, 1, key, test, best.distance2);
  return best;
}

}  // namespace adasculpt::geometry
