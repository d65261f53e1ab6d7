#include "geometry/mirror_tracker.h"

#include <algorithm>

#include "geometry/mirror_symmetry.h"
#include "mesh/vertex_mask.h"

namespace adasculpt::geometry {

void MirrorTracker::forget() {
  axis_ = -1;
  mask_odd_.clear();
  mask_odd_count_ = 0;
  index_.clear();
  map_.clear();
  clear_unknown();
  all_unknown_ = true;
  witnesses_.clear();
  coincident_[0] = coincident_[1] = mesh::Vertex();
}

void MirrorTracker::prepare(const mesh::SurfaceMesh& m, int axis) {
  forget();
  if (axis < 0 || axis > 2 || m.n_vertices() == 0) return;
  axis_ = axis;
  if (find_extent_witness(m)) return;
  // The index answers every later question, as after any change (two vertices at one point: no
  // map, and the pair is kept as the certificate).
  const bool distinct = index_.build(m);
  settle_from_index(m, distinct);
}

void MirrorTracker::clear_unknown() {
  for (mesh::Vertex v : unknown_)
    if (v.idx < in_unknown_.size()) in_unknown_[v.idx] = 0;
  unknown_.clear();
}

void MirrorTracker::mark_unknown(mesh::Vertex v) {
  if (all_unknown_ || v.idx >= in_unknown_.size() || in_unknown_[v.idx]) return;
  in_unknown_[v.idx] = 1;
  unknown_.push_back(v);
}

void MirrorTracker::forget_map() {
  clear_unknown();
  all_unknown_ = true;
}

// The witness's own position is compared (it may have moved back and forth): untouched vertices
// keep theirs, so only a touched one can have come to lie at the witness's mirror position.
bool MirrorTracker::witness_holds(const mesh::SurfaceMesh& m, const std::vector<mesh::Vertex>& touched,
                                  const Witness& w) const {
  if (w.v.idx >= m.vertices_size() || m.is_deleted(w.v) || !same_position(m.position(w.v), w.p)) return false;
  const Point q = mirrored(w.p);
  for (mesh::Vertex t : touched)
    if (t.idx < m.vertices_size() && !m.is_deleted(t) && same_position(m.position(t), q)) return false;
  return true;
}

// Whatever changed, two live vertices at one point mean no map (a slot reused since is checked
// like any other: by its position now).
bool MirrorTracker::coincidence_holds(const mesh::SurfaceMesh& m) const {
  const size_t n = m.vertices_size();
  const mesh::Vertex a = coincident_[0], b = coincident_[1];
  return a.is_valid() && b.is_valid() && a != b && a.idx < n && b.idx < n && !m.is_deleted(a) && !m.is_deleted(b) &&
         same_position(m.position(a), m.position(b));
}

void MirrorTracker::follow(const mesh::SurfaceMesh& m, const std::vector<mesh::Vertex>& touched) {
  if (axis_ < 0) return;
  const size_t n = m.vertices_size();
  if (index_.built()) index_.update(m, touched);
  witnesses_.erase(std::remove_if(witnesses_.begin(), witnesses_.end(),
                                  [&](const Witness& w) { return !witness_holds(m, touched, w); }),
                   witnesses_.end());
  if (!all_unknown_) {
    // D grows by the touched slots and by their images before the change, the slots an undo cut
    // off the end included (their partners stay, paired with nothing).
    in_unknown_.resize(std::max(n, in_unknown_.size()), 0);
    auto touch = [&](mesh::Vertex t) {
      mark_unknown(t);
      if (t.idx < map_.size() && map_[t.idx].is_valid()) mark_unknown(map_[t.idx]);
    };
    for (size_t v = n; v < map_.size(); ++v) touch(mesh::Vertex(mesh::Index(v)));
    for (mesh::Vertex t : touched) touch(t);
    for (size_t v = n; v < in_unknown_.size(); ++v) in_unknown_[v] = 0;  // listed ones are skipped when settled
    map_.resize(n, mesh::Vertex());  // (not while nothing is known: a mesh's worth of entries to fill)
    if (unknown_.size() > n / 8 + 64) forget_map();
  }
}

void MirrorTracker::follow_with_map(const mesh::SurfaceMesh& m, const std::vector<mesh::Vertex>& touched) {
  if (index_.built()) index_.update(m, touched);
  clear_unknown();
  all_unknown_ = false;
  witnesses_.clear();
  map_.resize(m.vertices_size(), mesh::Vertex());
  const mesh::VertexProperty<float> mask = mesh::find_mask(m);
  for (size_t v = m.vertices_size(); v < mask_odd_.size(); ++v) recount_mask(m, mask, mesh::Vertex(mesh::Index(v)));
  for (mesh::Vertex t : touched) {
    recount_mask(m, mask, t);
    if (t.idx < map_.size() && map_[t.idx].is_valid()) recount_mask(m, mask, map_[t.idx]);
  }
}

void MirrorTracker::recount_mask(const mesh::SurfaceMesh& m, const mesh::VertexProperty<float>& mask, mesh::Vertex v) {
  const bool odd = mask.is_valid() && v.idx < m.vertices_size() && !m.is_deleted(v) && map_[v.idx].is_valid() &&
                   mask[v] != mask[map_[v.idx]];
  if (mask_odd_.size() <= v.idx) {
    if (!odd) return;  // slots past the flags' end count as even (no mask yet, or new slots)
    mask_odd_.resize(m.vertices_size(), 0);
  }
  mask_odd_count_ = mask_odd_count_ - mask_odd_[v.idx] + odd;
  mask_odd_[v.idx] = odd;
}

// find_mirror_map's first test, the extent along the axis (the whole mesh is read, but nothing is
// hashed). When it is lopsided, every vertex beyond the mirror image of the near end has no vertex
// at its mirror position: up to kMaxWitnesses of them are kept, the first one in each of as many
// runs of slots, so that a stroke at one place (the far tip, say) does not take them all and send
// the next symmetric stroke back here.
bool MirrorTracker::find_extent_witness(const mesh::SurfaceMesh& m) {
  if (m.n_vertices() == 0) return false;
  last_settled_ += m.n_vertices();
  double l = m.position(*m.vertices().begin())[axis_], h = l;
  for (mesh::Vertex v : m.vertices()) {
    const double c = m.position(v)[axis_];
    l = std::min(l, c);
    h = std::max(h, c);
  }
  if (l == -h) return false;
  const bool high = h > -l;
  const size_t slots = m.vertices_size();
  size_t next_run = 0;  // the first run of slots still without a witness
  for (mesh::Vertex v : m.vertices()) {
    const size_t run = size_t(v.idx) * kMaxWitnesses / slots;
    if (run < next_run) continue;
    const double c = m.position(v)[axis_];
    if (high ? c > -l : c < -h) {
      add_witness(v, m.position(v));
      next_run = run + 1;
    }
  }
  return true;
}

void MirrorTracker::add_witness(mesh::Vertex v, const Point& p) {
  if (witnesses_.size() < kMaxWitnesses) witnesses_.push_back(Witness{v, p});
}

void MirrorTracker::count_mask_everywhere(const mesh::SurfaceMesh& m) {
  mask_odd_.clear();
  mask_odd_count_ = 0;
  if (const mesh::VertexProperty<float> mask = mesh::find_mask(m); mask.is_valid())
    for (mesh::Vertex v : m.vertices()) recount_mask(m, mask, v);
}

bool MirrorTracker::settle(const mesh::SurfaceMesh& m) {
  last_settled_ = 0;
  if (all_unknown_ && find_extent_witness(m)) return false;
  const size_t n = m.vertices_size();
  if (all_unknown_ && !index_.built()) {
    // The mesh's first question: a search is the quickest whole answer (its table is half the
    // index's size, and the index is built only once the changes need settling).
    std::vector<mesh::Vertex> image = find_mirror_map(m, axis_);
    if (!image.empty()) {
      last_settled_ += m.n_vertices();
      map_.swap(image);
      map_.resize(n, mesh::Vertex());
      all_unknown_ = false;
      count_mask_everywhere(m);
      return true;
    }
  }
  // A fresh index knows whether positions are distinct: then every probe stops at its match and
  // the pairs need no check (v's image's image is the one vertex at v's position).
  bool distinct = false;
  if (!index_.built() && !(distinct = index_.build(m))) return false;
  return settle_from_index(m, distinct);
}

bool MirrorTracker::settle_from_index(const mesh::SurfaceMesh& m, bool distinct) {
  const size_t n = m.vertices_size();
  in_unknown_.resize(n, 0);
  map_.resize(n, mesh::Vertex());
  const auto settle_one = [&](mesh::Vertex v) {
    ++last_settled_;
    const Point p = m.position(v);
    mesh::Vertex u, u2;
    const int found = index_.count_at(m, mirrored(p), &u, &u2);
    if (found == 0) {
      add_witness(v, p);
    } else if (found > 1) {
      coincident_[0] = u, coincident_[1] = u2;
    } else if (!all_unknown_ && !in_unknown_[u.idx]) {
      // An image outside D has its partner outside D at v's position: two vertices at one point.
      coincident_[0] = v, coincident_[1] = map_[u.idx];
      return false;
    }
    if (found != 1) return false;
    map_[v.idx] = u;
    return true;
  };
  const auto pairs_up = [&](mesh::Vertex v) { return map_[map_[v.idx].idx] == v; };
  if (all_unknown_ && distinct) {
    std::fill(map_.begin(), map_.end(), mesh::Vertex());
    for (mesh::Vertex v : m.vertices()) {
      ++last_settled_;
      const Point p = m.position(v);
      const mesh::Vertex u = index_.find(m, mirrored(p));
      if (!u.is_valid()) {
        add_witness(v, p);
        return false;
      }
      map_[v.idx] = u;
    }
  } else if (all_unknown_) {
    std::fill(map_.begin(), map_.end(), mesh::Vertex());
    for (mesh::Vertex v : m.vertices())
      if (!settle_one(v)) return false;
    for (mesh::Vertex v : m.vertices())
      if (!pairs_up(v)) return false;
  }
  if (all_unknown_) {
    count_mask_everywhere(m);
  } else {
    for (mesh::Vertex v : unknown_) {
      if (v.idx >= n || m.is_deleted(v)) {
        if (v.idx < n) map_[v.idx] = mesh::Vertex();
        continue;
      }
      if (!settle_one(v)) return false;
    }
    for (mesh::Vertex v : unknown_)
      if (v.idx < n && !m.is_deleted(v) && !pairs_up(v)) return false;
    const mesh::VertexProperty<float> mask = mesh::find_mask(m);
    for (mesh::Vertex v : unknown_) recount_mask(m, mask, v);
  }
  clear_unknown();
  all_unknown_ = false;
  return true;
}

std::vector<mesh::Vertex>* MirrorTracker::map(const mesh::SurfaceMesh& m, int axis) {
  last_settled_ = 0;
  if (axis < 0 || axis > 2 || m.n_vertices() == 0) return nullptr;
  if (axis != axis_) {
    axis_ = axis;
    forget_map();
    witnesses_.clear();
  }
  if (!witnesses_.empty() || coincidence_holds(m)) return nullptr;
  if (!all_unknown_ && unknown_.empty()) {
    map_.resize(m.vertices_size(), mesh::Vertex());
    return &map_;
  }
  return settle(m) ? &map_ : nullptr;
}

}  // namespace adasculpt::geometry
