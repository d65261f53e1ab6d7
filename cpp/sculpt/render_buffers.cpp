#include "sculpt/render_buffers.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "mesh/vertex_mask.h"

namespace adasculpt::sculpt {

using mesh::Face;
using mesh::SurfaceMesh;
using mesh::Vertex;

namespace {

void extend(std::uint32_t& begin, std::uint32_t& end, std::uint32_t b, std::uint32_t e) {
  if (b >= e) return;
  if (begin >= end) {
    begin = b;
    end = e;
  } else {
    begin = std::min(begin, b);
    end = std::max(end, e);
  }
}

}  // namespace

void RenderChanges::merge(const RenderChanges& later) {
  if (later.rebuilt) {  // the later box covers every vertex: what this one had is out of date
    std::copy_n(later.box_min, 3, box_min);
    std::copy_n(later.box_max, 3, box_max);
  } else {
    for (int k = 0; k < 3; ++k) {
      box_min[k] = std::min(box_min[k], later.box_min[k]);
      box_max[k] = std::max(box_max[k], later.box_max[k]);
    }
  }
  rebuilt = rebuilt || later.rebuilt;
  reallocated = reallocated || later.reallocated;
  indices_changed = indices_changed || later.indices_changed;
  extend(vertex_begin, vertex_end, later.vertex_begin, later.vertex_end);
  extend(face_begin, face_end, later.face_begin, later.face_end);
  vertex_count = later.vertex_count;
  face_count = later.face_count;
}

void RenderChanges::everything(std::uint32_t vertices, std::uint32_t faces) {
  indices_changed = true;
  vertex_begin = face_begin = 0;
  vertex_end = vertex_count = vertices;
  face_end = face_count = faces;
}

RenderChanges RenderBuffers::take_pending() {
  taken_dirty_faces_.swap(dirty_faces_);  // both keep their capacity: no allocation per frame
  dirty_faces_.clear();
  taken_all_dirty_ = all_dirty_;
  all_dirty_ = false;
  RenderChanges out = pending_;
  pending_ = RenderChanges{};
  pending_.vertex_count = vertex_count_;
  pending_.face_count = face_count_;
  return out;
}

bool RenderBuffers::reserve(size_t vertex_slots, size_t face_slots) {
  // 1.5x growth: a grab that keeps splitting reallocates O(log n) times, not once per frame.
  auto grown = [](size_t have, size_t need) { return std::max({need, have + have / 2, size_t(256)}); };
  bool realloc = false;
  if (vertex_slots > vertex_capacity() || positions_.empty()) {
    size_t cap = grown(vertex_capacity(), vertex_slots);
    positions_.resize(3 * cap, 0.0f);
    normals_.resize(3 * cap, 0.0f);
    masks_.resize(cap, 0.0f);
    stamp_.resize(cap, 0);
    realloc = true;
  }
  if (face_slots > face_capacity() || indices_.empty()) {
    indices_.resize(3 * grown(face_capacity(), face_slots), 0u);
    realloc = true;
  }
  return realloc;
}

void RenderBuffers::mark_normal(Vertex v) {
  if (stamp_[v.idx] == epoch_) return;
  stamp_[v.idx] = epoch_;
  normal_queue_.push_back(v);
}

void RenderBuffers::mark_face_dirty(std::uint32_t slot) {
  if (all_dirty_) return;
  // A reader that never takes the list (the CLI, most tests) must not grow it without bound: past
  // the slot count, "all of them" says as much.
  if (dirty_faces_.size() >= std::max<size_t>(face_count_, 1024)) {
    all_dirty_ = true;
    dirty_faces_.clear();
    return;
  }
  dirty_faces_.push_back(slot);
}

void RenderBuffers::write_position(const SurfaceMesh& m, Vertex v) {
  ++work_;
  const Point& p = m.position(v);
  float* out = &positions_[3 * size_t(v.idx)];
  out[0] = float(p.x);
  out[1] = float(p.y);
  out[2] = float(p.z);
  for (int k = 0; k < 3; ++k) {
    last_.box_min[k] = std::min(last_.box_min[k], out[k]);
    last_.box_max[k] = std::max(last_.box_max[k], out[k]);
  }
  masks_[v.idx] = mask_.is_valid() ? mask_[v] : 0.0f;
}

// Area-weighted average of the incident face normals: the sum of the corner cross products.
// Angle weights (an atan2 per corner) cost three times as much per frame, and the remesher keeps
// triangles well shaped, where the two agree closely.
void RenderBuffers::write_normal(const SurfaceMesh& m, Vertex v) {
  ++work_;
  Vec3 n(0.0);
  const Point& p = m.position(v);
  for (mesh::Halfedge h : m.halfedges(v)) {
    if (m.is_boundary(h)) continue;
    n += glm::cross(m.position(m.to_vertex(h)) - p, m.position(m.to_vertex(m.next(h))) - p);
  }
  double ln = glm::length(n);
  if (ln > 0.0 && std::isfinite(ln)) {
    n /= ln;
  } else {
    n = Vec3(0.0, 0.0, 1.0);
  }
  float* out = &normals_[3 * size_t(v.idx)];
  out[0] = float(n.x);
  out[1] = float(n.y);
  out[2] = float(n.z);
}

// The triple drawn for a face slot: its vertices, or (0,0,0) for a deleted face.
static void current_triple(const SurfaceMesh& m, Face f, std::uint32_t t[3]) {
  t[0] = t[1] = t[2] = 0;
  if (m.is_deleted(f)) return;
  Vertex fv[3];
  m.face_vertices(f, fv);
  for (int i = 0; i < 3; ++i) t[i] = fv[i].idx;
}

bool RenderBuffers::write_face(const SurfaceMesh& m, Face f) {
  ++work_;
  std::uint32_t* out = &indices_[3 * size_t(f.idx)];
  std::uint32_t t[3];
  current_triple(m, f, t);
  if (out[0] == t[0] && out[1] == t[1] && out[2] == t[2]) return false;
  // The vertices that lost this face and those that gained it both need new normals (an empty
  // slot, all zeros, had no vertices).
  const std::uint32_t nv = std::uint32_t(m.vertices_size());
  const bool was_empty = (out[0] | out[1] | out[2]) == 0;
  for (int i = 0; i < 3; ++i) {
    if (!was_empty && out[i] < nv && out[i] < vertex_count_ && !m.is_deleted(Vertex(out[i])))
      mark_normal(Vertex(out[i]));
    if (!m.is_deleted(f)) mark_normal(Vertex(t[i]));
    out[i] = t[i];
  }
  return true;
}

const RenderChanges& RenderBuffers::rebuild(const SurfaceMesh& m) {
  mask_ = mesh::find_mask(m);
  const std::uint32_t nv = std::uint32_t(m.vertices_size());
  const std::uint32_t nf = std::uint32_t(m.faces_size());
  last_ = RenderChanges{};
  // Room for the slots the next strokes add (as SurfaceMesh::reserve_room_for_edits): sized
  // exactly, the first split after a load reallocated every buffer and sent them all again, which
  // cost the first stroke on 1.1M triangles ~15 ms natively (a full upload in the browser; issue 18).
  auto room = [](size_t n) { return n + n / 8 + 16; };
  last_.reallocated = reserve(room(nv), room(nf));
  for (std::uint32_t i = 0; i < nv; ++i) {
    Vertex v(i);
    if (m.is_deleted(v)) {
      std::fill_n(&positions_[3 * size_t(i)], 3, 0.0f);
      std::fill_n(&normals_[3 * size_t(i)], 3, 0.0f);
      masks_[i] = 0.0f;
    } else {
      write_position(m, v);
      write_normal(m, v);
    }
  }
  for (std::uint32_t i = 0; i < nf; ++i) current_triple(m, Face(i), &indices_[3 * size_t(i)]);
  // Slots beyond the new counts keep nothing drawable.
  std::fill(indices_.begin() + 3 * size_t(nf), indices_.begin() + 3 * size_t(std::max(nf, face_count_)), 0u);
  vertex_count_ = nv;
  face_count_ = nf;
  work_ = size_t(nv) + nf;
  last_.rebuilt = true;
  last_.everything(nv, nf);
  all_dirty_ = true;
  dirty_faces_.clear();
  pending_.merge(last_);
  return last_;
}

const RenderChanges& RenderBuffers::update(const SurfaceMesh& m, const Vertex* touched, size_t n_touched,
                                           const Face* faces, size_t n_faces, bool topology_changed,
                                           bool everything) {
  mask_ = mesh::find_mask(m);
  const std::uint32_t nv = std::uint32_t(m.vertices_size());
  const std::uint32_t nf = std::uint32_t(m.faces_size());
  if (everything || positions_.empty()) return rebuild(m);

  work_ = 0;
  last_ = RenderChanges{};
  last_.reallocated = reserve(nv, nf);
  if (++epoch_ == 0) {  // wrapped: forget all stamps once every 4 billion updates
    std::fill(stamp_.begin(), stamp_.end(), 0u);
    epoch_ = 1;
  }
  normal_queue_.clear();
  std::uint32_t fb = 0, fe = 0;
  // Fewer slots: an undo took back the slots a step had appended (sculpt/undo_log.h). Their
  // triangles are emptied; the vertices they leave get new normals (those still in the mesh).
  if (nf < face_count_) {
    work_ += face_count_ - nf;
    for (std::uint32_t i = nf; i < face_count_; ++i) {
      mark_face_dirty(i);
      std::uint32_t* t = &indices_[3 * size_t(i)];
      for (int k = 0; k < 3; ++k)
        if ((t[0] | t[1] | t[2]) != 0 && t[k] < nv && !m.is_deleted(Vertex(t[k]))) mark_normal(Vertex(t[k]));
      t[0] = t[1] = t[2] = 0;
    }
    extend(fb, fe, nf, face_count_);
    face_count_ = nf;
  }
  if (nv < vertex_count_) vertex_count_ = nv;

  // Faces: every face whose triangle changed is incident to a touched live vertex (the contract
  // in the header), is a new slot, or is one of the touched faces (the deleted ones). So: the
  // faces around touched vertices, the new slots and the touched faces; no walk over the slots.
  const bool faces_may_change = topology_changed || nf != face_count_ || fe > fb || n_faces > 0;
  auto face = [&](Face f) {
    if (!write_face(m, f)) return;
    extend(fb, fe, f.idx, f.idx + 1);
    mark_face_dirty(f.idx);
  };
  auto moved = [&](Vertex v) {
    write_position(m, v);
    mark_normal(v);
    for (Vertex w : m.vertices(v)) mark_normal(w);
    for (Face f : m.faces(v)) {
      if (faces_may_change && write_face(m, f)) extend(fb, fe, f.idx, f.idx + 1);
      mark_face_dirty(f.idx);  // rewritten or not, its corner moved
    }
  };
  for (size_t i = 0; i < n_touched; ++i) {
    Vertex v = touched[i];
    if (v.idx < nv && !m.is_deleted(v)) moved(v);
  }
  for (std::uint32_t i = vertex_count_; i < nv; ++i) {
    if (!m.is_deleted(Vertex(i))) moved(Vertex(i));
  }
  if (faces_may_change) {
    for (std::uint32_t i = face_count_; i < nf; ++i) face(Face(i));
    for (size_t i = 0; i < n_faces; ++i)
      if (faces[i].idx < face_count_) face(faces[i]);  // slots past it were just written
    last_.face_begin = fb;
    last_.face_end = fe;
    last_.indices_changed = fe > fb;
  }
  vertex_count_ = nv;
  face_count_ = nf;

  std::uint32_t vb = 0, ve = 0;
  for (Vertex v : normal_queue_) {
    write_normal(m, v);
    extend(vb, ve, v.idx, v.idx + 1);
  }
  last_.vertex_begin = vb;
  last_.vertex_end = ve;
  last_.vertex_count = nv;
  last_.face_count = nf;
  if (last_.reallocated) {  // new arrays on the GPU side: upload all again
    last_.everything(nv, nf);
    all_dirty_ = true;
    dirty_faces_.clear();
  }
  pending_.merge(last_);
  return last_;
}

}  // namespace adasculpt::sculpt
