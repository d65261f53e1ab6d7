#include "geometry/position_index.h"

#include <algorithm>
#include <cstring>

namespace adasculpt::geometry {

namespace {
std::uint64_t bits_of(double c) {
  if (c == 0) c = 0.0;
  std::uint64_t b;
  std::memcpy(&b, &c, sizeof b);
  return b;
}
// A slot deleted by a change not yet followed may still be filed: it is not a vertex.
bool live_at(const mesh::SurfaceMesh& m, std::uint32_t v, const Point& p) {
  return same_position(m.position(mesh::Vertex(v)), p) && !m.is_deleted(mesh::Vertex(v));
}
}  // namespace

bool same_position(const Point& a, const Point& b) {
  for (int i = 0; i < 3; ++i)
    if (bits_of(a[i]) != bits_of(b[i])) return false;
  return true;
}

std::uint64_t position_hash(const Point& p) {
  std::uint64_t h = 0x9e3779b97f4a7c15ull;
  for (int i = 0; i < 3; ++i) {
    h = (h ^ bits_of(p[i])) * 0xff51afd7ed558ccdull;
    h ^= h >> 32;
  }
  return h;
}

void PositionIndex::clear() {
  table_.clear();
  table_.shrink_to_fit();
  home_.clear();
  home_.shrink_to_fit();
  filed_ = 0;
}

bool PositionIndex::build(const mesh::SurfaceMesh& m) {
  size_t size = 16;
  while (size < 2 * m.n_vertices() + 2) size *= 2;
  table_.assign(size, Entry{kEmpty, 0});
  home_.assign(m.vertices_size(), kEmpty);
  filed_ = 0;
  bool distinct = true;
  for (mesh::Vertex v : m.vertices()) distinct = insert(m, v.idx) && distinct;
  return distinct;
}

void PositionIndex::grow(const mesh::SurfaceMesh& m) {
  std::vector<std::uint32_t> slots;
  slots.reserve(filed_);
  for (const Entry& e : table_)
    if (e.slot != kEmpty) slots.push_back(e.slot);
  table_.assign(table_.size() * 2, Entry{kEmpty, 0});
  filed_ = 0;
  std::sort(slots.begin(), slots.end());  // the same table whatever order the old one held them in
  for (std::uint32_t v : slots) {
    home_[v] = kEmpty;
    insert(m, v);
  }
}

bool PositionIndex::insert(const mesh::SurfaceMesh& m, std::uint32_t v) {
  if (2 * (filed_ + 1) > table_.size()) grow(m);
  const size_t mask = table_.size() - 1;
  const Point& p = m.position(mesh::Vertex(v));
  const std::uint32_t key = std::uint32_t(position_hash(p));
  size_t b = key & mask;
  bool distinct = true;
  for (; table_[b].slot != kEmpty; b = (b + 1) & mask)
    if (table_[b].key == key && same_position(m.position(mesh::Vertex(table_[b].slot)), p)) distinct = false;
  table_[b] = Entry{v, key};
  home_[v] = std::uint32_t(key & mask);
  ++filed_;
  return distinct;
}

void PositionIndex::erase(std::uint32_t v) {
  const size_t mask = table_.size() - 1;
  size_t b = home_[v];
  while (table_[b].slot != v) b = (b + 1) & mask;  // filed at or after its home, before the next gap
  home_[v] = kEmpty;
  --filed_;
  // Backward shift: an entry further on whose home is not in (gap, entry] moves into the gap, so
  // every entry stays reachable from its home without crossing an empty bucket.
  size_t gap = b;
  for (size_t next = (gap + 1) & mask; table_[next].slot != kEmpty; next = (next + 1) & mask) {
    const size_t home = table_[next].key & mask;
    const bool stays = gap <= next ? (gap < home && home <= next) : (gap < home || home <= next);
    if (stays) continue;
    table_[gap] = table_[next];
    gap = next;
  }
  table_[gap] = Entry{kEmpty, 0};
}

void PositionIndex::update(const mesh::SurfaceMesh& m, const std::vector<mesh::Vertex>& slots) {
  const size_t n = m.vertices_size();
  for (size_t v = n; v < home_.size(); ++v)
    if (home_[v] != kEmpty) erase(std::uint32_t(v));
  home_.resize(n, kEmpty);
  for (mesh::Vertex v : slots) {
    if (v.idx >= n) continue;
    if (home_[v.idx] != kEmpty) erase(v.idx);
    if (!m.is_deleted(v)) insert(m, v.idx);
  }
}

mesh::Vertex PositionIndex::find(const mesh::SurfaceMesh& m, const Point& p) const {
  if (table_.empty()) return mesh::Vertex();
  const size_t mask = table_.size() - 1;
  const std::uint32_t key = std::uint32_t(position_hash(p));
  for (size_t b = key & mask; table_[b].slot != kEmpty; b = (b + 1) & mask)
    if (table_[b].key == key && live_at(m, table_[b].slot, p)) return mesh::Vertex(table_[b].slot);
  return mesh::Vertex();
}

int PositionIndex::count_at(const mesh::SurfaceMesh& m, const Point& p, mesh::Vertex* first,
                            mesh::Vertex* second) const {
  if (table_.empty()) return 0;
  const size_t mask = table_.size() - 1;
  const std::uint32_t key = std::uint32_t(position_hash(p));
  int count = 0;
  for (size_t b = key & mask; table_[b].slot != kEmpty; b = (b + 1) & mask) {
    if (table_[b].key != key || !live_at(m, table_[b].slot, p)) continue;
    if (count == 0 && first) *first = mesh::Vertex(table_[b].slot);
    if (count == 1 && second) *second = mesh::Vertex(table_[b].slot);
    ++count;
  }
  return count;
}

}  // namespace adasculpt::geometry
