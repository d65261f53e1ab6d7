#include "sculpt/component_box.h"

#include <algorithm>

#include <glm/geometric.hpp>

#include "mesh/flat_walk.h"

namespace adasculpt::sculpt {

void ComponentBox::reset(size_t vertex_slots) {
  followed_ = false;
  grow_marks(vertex_slots);
}

void ComponentBox::grow_marks(size_t vertex_slots) {
  if (mark_.size() < vertex_slots) mark_.resize(vertex_slots * 5 / 4 + 16, 0u);  // room for strokes' growth
}

double ComponentBox::measure(const mesh::SurfaceMesh& m, mesh::Vertex v) {
  grow_marks(m.vertices_size());
  if (++run_ == 0) {
    std::fill(mark_.begin(), mark_.end(), 0u);
    run_ = 1;
  }
  lo_ = hi_ = m.position(v);
  std::fill(side_, side_ + 6, v);
  queue_.assign(1, v);
  mark_[v.idx] = run_;
  const auto* hc = m.halfedge_connectivity_data();
  const mesh::Halfedge* vh = m.vertex_halfedge_data();
  for (size_t i = 0; i < queue_.size(); ++i) {
    const mesh::Vertex u = queue_[i];
    const Point& p = m.position(u);
    for (int a = 0; a < 3; ++a) {
      if (p[a] < lo_[a]) lo_[a] = p[a], side_[a] = u;
      if (p[a] > hi_[a]) hi_[a] = p[a], side_[3 + a] = u;
    }
    mesh::for_each_outgoing(hc, vh, u, [&](mesh::Halfedge h) {
      const mesh::Vertex w = hc[h.idx].to;
      if (mark_[w.idx] != run_) {
        mark_[w.idx] = run_;
        queue_.push_back(w);
      }
    });
  }
  followed_ = true;
  return glm::length(hi_ - lo_);
}

double ComponentBox::known_diagonal(const mesh::SurfaceMesh& m, mesh::Vertex v) const {
  if (!followed_ || v.idx >= m.vertices_size() || m.is_deleted(v) || !member(v)) return 0;
  return glm::length(hi_ - lo_);
}

void ComponentBox::follow(const mesh::SurfaceMesh& m, const std::vector<mesh::Vertex>& touched) {
  if (!followed_) return;
  const size_t n = m.vertices_size();
  grow_marks(n);
  // Which touched vertices are the component's now. Untouched vertices kept their marks (an edit
  // adds no vertex it does not touch), and a touched member is joined to an untouched one through
  // touched vertices (the component has untouched vertices: those at its sides, checked below).
  for (mesh::Vertex v : touched)
    if (v.idx < mark_.size()) mark_[v.idx] = 0;
  const auto* hc = m.halfedge_connectivity_data();
  const mesh::Halfedge* vh = m.vertex_halfedge_data();
  queue_.clear();
  for (mesh::Vertex v : touched) {
    if (v.idx >= n || m.is_deleted(v) || member(v)) continue;
    bool joined = false;
    mesh::for_each_outgoing(hc, vh, v, [&](mesh::Halfedge h) { joined = joined || member(hc[h.idx].to); });
    if (!joined) continue;
    mark_[v.idx] = run_;
    queue_.push_back(v);
  }
  for (size_t i = 0; i < queue_.size(); ++i)
    mesh::for_each_outgoing(hc, vh, queue_[i], [&](mesh::Halfedge h) {
      const mesh::Vertex w = hc[h.idx].to;
      if (!member(w)) {  // a neighbour of the component is in it: touched, since others kept their marks
        mark_[w.idx] = run_;
        queue_.push_back(w);
      }
    });
  // Each side still has a vertex at it (or beyond it: the touched ones extend the box below).
  for (int k = 0; k < 6; ++k) {
    const mesh::Vertex s = side_[k];
    const int a = k % 3;
    const bool still = s.idx < n && !m.is_deleted(s) && member(s) &&
                       (k < 3 ? m.position(s)[a] <= lo_[a] : m.position(s)[a] >= hi_[a]);
    if (!still) {
      followed_ = false;
      return;
    }
  }
  for (mesh::Vertex u : queue_) {
    const Point& p = m.position(u);
    for (int a = 0; a < 3; ++a) {
      if (p[a] < lo_[a]) lo_[a] = p[a], side_[a] = u;
      if (p[a] > hi_[a]) hi_[a] = p[a], side_[3 + a] = u;
    }
  }
}

}  // namespace adasculpt::sculpt
