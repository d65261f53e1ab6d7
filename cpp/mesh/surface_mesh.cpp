#include "mesh/surface_mesh.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include <glm/common.hpp>

namespace adasculpt::mesh {

SurfaceMesh::SurfaceMesh() {
  points_ = VertexProperty<Point>(vprops_.add<Point>("v:point", Point(0.0)));
  vconn_ = VertexProperty<Halfedge>(vprops_.add<Halfedge>("v:connectivity", Halfedge()));
  hconn_ = HalfedgeProperty<HalfedgeConnectivity>(hprops_.add<HalfedgeConnectivity>("h:connectivity", {}));
  fconn_ = FaceProperty<Halfedge>(fprops_.add<Halfedge>("f:connectivity", Halfedge()));
  vdeleted_ = VertexProperty<std::uint8_t>(vprops_.add<std::uint8_t>("v:deleted", 0));
  edeleted_ = EdgeProperty<std::uint8_t>(eprops_.add<std::uint8_t>("e:deleted", 0));
  fdeleted_ = FaceProperty<std::uint8_t>(fprops_.add<std::uint8_t>("f:deleted", 0));
}

void SurfaceMesh::bind_builtin_properties() {
  points_ = get_vertex_property<Point>("v:point");
  vconn_ = get_vertex_property<Halfedge>("v:connectivity");
  hconn_ = HalfedgeProperty<HalfedgeConnectivity>(hprops_.get<HalfedgeConnectivity>("h:connectivity"));
  fconn_ = get_face_property<Halfedge>("f:connectivity");
  vdeleted_ = get_vertex_property<std::uint8_t>("v:deleted");
  edeleted_ = get_edge_property<std::uint8_t>("e:deleted");
  fdeleted_ = get_face_property<std::uint8_t>("f:deleted");
}

SurfaceMesh::SurfaceMesh(const SurfaceMesh& o)
    : vprops_(o.vprops_),
      hprops_(o.hprops_),
      eprops_(o.eprops_),
      fprops_(o.fprops_),
      deleted_vertices_(o.deleted_vertices_),
      deleted_edges_(o.deleted_edges_),
      deleted_faces_(o.deleted_faces_) {
  bind_builtin_properties();
}

SurfaceMesh& SurfaceMesh::operator=(const SurfaceMesh& o) {
  if (this != &o) {
    SurfaceMesh copy(o);
    *this = std::move(copy);
  }
  return *this;
}

// Moving the containers keeps the heap-allocated arrays, so the bound pointers stay valid.
SurfaceMesh::SurfaceMesh(SurfaceMesh&& o) noexcept
    : vprops_(std::move(o.vprops_)),
      hprops_(std::move(o.hprops_)),
      eprops_(std::move(o.eprops_)),
      fprops_(std::move(o.fprops_)),
      points_(o.points_),
      vconn_(o.vconn_),
      hconn_(o.hconn_),
      fconn_(o.fconn_),
      vdeleted_(o.vdeleted_),
      edeleted_(o.edeleted_),
      fdeleted_(o.fdeleted_),
      deleted_vertices_(o.deleted_vertices_),
      deleted_edges_(o.deleted_edges_),
      deleted_faces_(o.deleted_faces_) {
  o = SurfaceMesh();
}

SurfaceMesh& SurfaceMesh::operator=(SurfaceMesh&& o) noexcept {
  if (this != &o) {
    vprops_ = std::move(o.vprops_);
    hprops_ = std::move(o.hprops_);
    eprops_ = std::move(o.eprops_);
    fprops_ = std::move(o.fprops_);
    points_ = o.points_;
    vconn_ = o.vconn_;
    hconn_ = o.hconn_;
    fconn_ = o.fconn_;
    vdeleted_ = o.vdeleted_;
    edeleted_ = o.edeleted_;
    fdeleted_ = o.fdeleted_;
    deleted_vertices_ = o.deleted_vertices_;
    deleted_edges_ = o.deleted_edges_;
    deleted_faces_ = o.deleted_faces_;
    o.vprops_ = PropertyContainer();
    o.hprops_ = PropertyContainer();
    o.eprops_ = PropertyContainer();
    o.fprops_ = PropertyContainer();
    // Leave the source as a valid empty mesh.
    SurfaceMesh fresh;
    o.vprops_ = std::move(fresh.vprops_);
    o.hprops_ = std::move(fresh.hprops_);
    o.eprops_ = std::move(fresh.eprops_);
    o.fprops_ = std::move(fresh.fprops_);
    o.bind_builtin_properties();
    o.deleted_vertices_ = o.deleted_edges_ = o.deleted_faces_ = 0;
  }
  return *this;
}

void SurfaceMesh::clear() {
  vprops_.resize(0);
  hprops_.resize(0);
  eprops_.resize(0);
  fprops_.resize(0);
  deleted_vertices_ = deleted_edges_ = deleted_faces_ = 0;
}

void SurfaceMesh::reserve(size_t nv, size_t ne, size_t nf) {
  vprops_.reserve(nv);
  hprops_.reserve(2 * ne);
  eprops_.reserve(ne);
  fprops_.reserve(nf);
}

Vertex SurfaceMesh::add_vertex(const Point& p) {
  // Copy first: p may refer into the position array that push_back is about to reallocate.
  const Point position = p;
  vprops_.push_back();
  Vertex v(static_cast<Index>(vprops_.size() - 1));
  points_[v] = position;
  return v;
}

Halfedge SurfaceMesh::new_edge(Vertex from, Vertex to) {
  eprops_.push_back();
  hprops_.push_back();
  hprops_.push_back();
  Halfedge h(static_cast<Index>(hprops_.size() - 2));
  hconn_[h].to = to;
  hconn_[opposite(h)].to = from;
  return h;
}

Face SurfaceMesh::new_face() {
  fprops_.push_back();
  return Face(static_cast<Index>(fprops_.size() - 1));
}

bool SurfaceMesh::is_boundary(Face f) const {
  for (Halfedge h : halfedges(f))
    if (is_boundary(opposite(h))) return true;
  return false;
}

size_t SurfaceMesh::valence(Vertex v) const {
  size_t n = 0;
  for ([[maybe_unused]] Halfedge h : halfedges(v)) ++n;
  return n;
}

Halfedge SurfaceMesh::find_halfedge(Vertex a, Vertex b) const {
  for (Halfedge h : halfedges(a))
    if (to_vertex(h) == b) return h;
  return Halfedge();
}

void SurfaceMesh::delete_vertex_mark(Vertex v) {
  if (!vdeleted_[v]) {
    vdeleted_[v] = 1;
    ++deleted_vertices_;
  }
}
void SurfaceMesh::delete_edge_mark(Edge e) {
  if (!edeleted_[e]) {
    edeleted_[e] = 1;
    ++deleted_edges_;
  }
}
void SurfaceMesh::delete_face_mark(Face f) {
  if (!fdeleted_[f]) {
    fdeleted_[f] = 1;
    ++deleted_faces_;
  }
}

// Makes halfedge(v) a boundary halfedge when v is on the boundary (the class invariant).
void SurfaceMesh::fix_outgoing_halfedge(Vertex v) {
  Halfedge start = halfedge(v);
  if (!start.is_valid()) return;
  Halfedge h = start;
  do {
    if (is_boundary(h)) {
      set_halfedge(v, h);
      return;
    }
    h = cw_rotated(h);
  } while (h != start);
}

Vertex SurfaceMesh::split(Edge e, const Point& p) {
  Halfedge h0 = halfedge(e, 0);  // a -> b, becomes a -> v
  Halfedge o0 = halfedge(e, 1);  // b -> a, becomes v -> a
  Vertex b = to_vertex(h0);
  Vertex v = add_vertex(p);
  Halfedge t1 = new_edge(v, b);  // v -> b
  Halfedge o1 = opposite(t1);    // b -> v
  set_vertex(h0, v);

  // Side of h0.
  if (!is_boundary(h0)) {
    Face f0 = face(h0);
    Halfedge n0 = next(h0);  // b -> c
    Halfedge p0 = prev(h0);  // c -> a
    Vertex c = to_vertex(n0);
    Face f2 = new_face();
    Halfedge vc = new_edge(v, c);
    Halfedge cv = opposite(vc);
    set_next(h0, vc);
    set_next(vc, p0);
    set_next(p0, h0);
    set_face(vc, f0);
    set_halfedge(f0, h0);
    set_next(t1, n0);
    set_next(n0, cv);
    set_next(cv, t1);
    set_face(t1, f2);
    set_face(n0, f2);
    set_face(cv, f2);
    set_halfedge(f2, t1);
  } else {
    Halfedge n0 = next(h0);
    set_next(t1, n0);
    set_next(h0, t1);
    set_face(t1, Face());
  }

  // Side of o0 (was b -> a, now v -> a).
  if (!is_boundary(o0)) {
    Face g0 = face(o0);
    Halfedge n1 = next(o0);  // a -> d
    Halfedge p1 = prev(o0);  // d -> b
    Vertex d = to_vertex(n1);
    Face g2 = new_face();
    Halfedge vd = new_edge(v, d);
    Halfedge dv = opposite(vd);
    set_next(o1, vd);
    set_next(vd, p1);
    set_next(p1, o1);
    set_face(o1, g0);
    set_face(vd, g0);
    set_halfedge(g0, o1);
    set_next(o0, n1);
    set_next(n1, dv);
    set_next(dv, o0);
    set_face(o0, g2);
    set_face(n1, g2);
    set_face(dv, g2);
    set_halfedge(g2, o0);
  } else {
    Halfedge p1 = prev(o0);
    set_next(p1, o1);
    set_next(o1, o0);
    set_face(o1, Face());
  }

  if (halfedge(b) == o0) set_halfedge(b, o1);
  if (is_boundary(o0))
    set_halfedge(v, o0);
  else
    set_halfedge(v, t1);  // boundary when h0 was, which keeps the invariant
  return v;
}

bool SurfaceMesh::is_collapse_ok(Halfedge h) const {
  Halfedge o = opposite(h);
  Vertex v0 = to_vertex(o), v1 = to_vertex(h);
  bool h_boundary = is_boundary(h), o_boundary = is_boundary(o);

  // An interior edge between two boundary vertices would pinch the surface.
  if (!h_boundary && !o_boundary && is_boundary(v0) && is_boundary(v1)) return false;

  Vertex x, y;  // the tips of the triangles that disappear
  if (!h_boundary) {
    x = to_vertex(next(h));
    // An ear triangle: both other edges on the boundary would leave a dangling edge.
    if (is_boundary(opposite(next(h))) && is_boundary(opposite(prev(h)))) return false;
    if (!is_boundary(x) && valence(x) <= 3) return false;
  }
  if (!o_boundary) {
    y = to_vertex(next(o));
    if (is_boundary(opposite(next(o))) && is_boundary(opposite(prev(o)))) return false;
    if (!is_boundary(y) && valence(y) <= 3) return false;
  }
  if (x.is_valid() && x == y) return false;

  // Link condition: the common neighbours of v0 and v1 are exactly x and y. v1's ring is
  // gathered once into a small buffer (valences are rarely above a dozen).
  constexpr size_t kRingBuffer = 64;
  Vertex ring[kRingBuffer];
  size_t n = 0;
  for (Halfedge b : halfedges(v1)) {
    if (n == kRingBuffer) break;
    ring[n++] = to_vertex(b);
  }
  const bool complete = n < kRingBuffer;
  for (Halfedge a : halfedges(v0)) {
    Vertex w = to_vertex(a);
    if (w == v1 || w == x || w == y) continue;
    if (complete) {
      for (size_t i = 0; i < n; ++i)
        if (ring[i] == w) return false;
    } else {
      for (Halfedge b : halfedges(v1))
        if (to_vertex(b) == w) return false;
    }
  }
  return true;
}

// After the collapse a triangle has become the two-gon (keep, remove) between the same two
// vertices; `keep` takes the place of opposite(remove) and the edge of `remove` goes away.
void SurfaceMesh::remove_loop_after_collapse(Halfedge keep, Halfedge remove) {
  Halfedge outer = opposite(remove);  // same direction as keep
  Face f = face(keep);
  Face g = face(outer);
  Vertex a = to_vertex(opposite(keep));  // from_vertex(keep)
  Vertex b = to_vertex(keep);

  set_next(prev(outer), keep);
  set_next(keep, next(outer));
  set_face(keep, g);
  if (g.is_valid() && halfedge(g) == outer) set_halfedge(g, keep);
  if (halfedge(a) == outer) set_halfedge(a, keep);
  if (halfedge(b) == remove) set_halfedge(b, opposite(keep));

  delete_face_mark(f);
  delete_edge_mark(edge(remove));
}

void SurfaceMesh::collapse(Halfedge h) {
  Halfedge o = opposite(h);
  Vertex v0 = to_vertex(o), v1 = to_vertex(h);
  Halfedge hn = next(h), hp = prev(h), on = next(o), op = prev(o);
  bool h_boundary = is_boundary(h), o_boundary = is_boundary(o);

  // Incoming halfedges of v0 now end at v1.
  for (Halfedge out : halfedges(v0)) set_vertex(opposite(out), v1);

  // Unlink h and o from their cycles.
  set_next(hp, hn);
  set_next(op, on);

  // An outgoing halfedge of v1 that survives: v1 -> x, or v1 -> y when h was on the boundary
  // (next(h) may belong to the edge that is removed with the triangle on the other side).
  Halfedge survivor = h_boundary ? on : opposite(hp);
  if (!h_boundary) {
    // Triangle (v0, v1, x) is now the two-gon hn: v1->x, hp: x->v1. Keep hp's edge.
    remove_loop_after_collapse(hp, hn);
  }
  if (!o_boundary) {
    // Triangle (v1, v0, y) is now the two-gon on: v1->y, op: y->v1. Keep on's edge.
    remove_loop_after_collapse(on, op);
  }
  set_halfedge(v1, survivor);
  fix_outgoing_halfedge(v1);

  set_halfedge(v0, Halfedge());
  delete_vertex_mark(v0);
  delete_edge_mark(edge(h));
}

bool SurfaceMesh::is_flip_ok(Edge e) const {
  if (is_boundary(e)) return false;
  Halfedge h = halfedge(e, 0), o = halfedge(e, 1);
  Vertex a = to_vertex(o), b = to_vertex(h);
  Vertex c = to_vertex(next(h)), d = to_vertex(next(o));
  if (c == d) return false;
  if (find_halfedge(c, d).is_valid()) return false;
  // An interior vertex of valence 3 would be left with two faces on one edge pair.
  if (!is_boundary(a) && valence(a) <= 3) return false;
  if (!is_boundary(b) && valence(b) <= 3) return false;
  return true;
}

void SurfaceMesh::flip(Edge e) {
  Halfedge h = halfedge(e, 0);  // a -> b, becomes d -> c
  Halfedge o = halfedge(e, 1);  // b -> a, becomes c -> d
  Halfedge hn = next(h), hp = prev(h);  // b -> c, c -> a
  Halfedge on = next(o), op = prev(o);  // a -> d, d -> b
  Vertex a = to_vertex(o), b = to_vertex(h);
  Vertex c = to_vertex(hn), d = to_vertex(on);
  Face f1 = face(h), f2 = face(o);

  set_vertex(h, c);
  set_vertex(o, d);
  // f1 = (c -> a, a -> d, d -> c); f2 = (d -> b, b -> c, c -> d)
  set_next(hp, on);
  set_next(on, h);
  set_next(h, hp);
  set_next(op, hn);
  set_next(hn, o);
  set_next(o, op);
  set_face(on, f1);
  set_face(hn, f2);
  set_halfedge(f1, h);
  set_halfedge(f2, o);
  if (halfedge(a) == h) set_halfedge(a, on);
  if (halfedge(b) == o) set_halfedge(b, hn);
}

void SurfaceMesh::reserve_room_for_edits() {
  auto room = [](size_t n) { return n + n / 8 + 16; };
  reserve(room(vertices_size()), room(edges_size()), room(faces_size()));
}

void SurfaceMesh::garbage_collection() {
  if (!has_garbage()) return;
  std::vector<Index> vkeep, ekeep, fkeep;
  vkeep.reserve(n_vertices());
  ekeep.reserve(n_edges());
  fkeep.reserve(n_faces());
  for (Index i = 0; i < vertices_size(); ++i)
    if (!vdeleted_[Vertex(i)]) vkeep.push_back(i);
  for (Index i = 0; i < edges_size(); ++i)
    if (!edeleted_[Edge(i)]) ekeep.push_back(i);
  for (Index i = 0; i < faces_size(); ++i)
    if (!fdeleted_[Face(i)]) fkeep.push_back(i);
  compact_to(vkeep, ekeep, fkeep);
}

namespace {
// The bits of a 21-bit integer spread to every third bit (the Morton code's one axis).
std::uint64_t spread_bits(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffull;
  x = (x | x << 16) & 0x1f0000ff0000ffull;
  x = (x | x << 8) & 0x100f00f00f00f00full;
  x = (x | x << 4) & 0x10c30c30c30c30c3ull;
  x = (x | x << 2) & 0x1249249249249249ull;
  return x;
}
}  // namespace

void SurfaceMesh::sort_in_space() {
  // The live vertices by the Morton code of their position in the bounding box (ties, which only
  // coincident points make, by slot: the order is deterministic).
  Point lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (Vertex v : vertices()) {
    lo = glm::min(lo, position(v));
    hi = glm::max(hi, position(v));
  }
  std::vector<std::pair<std::uint64_t, Index>> keyed;
  keyed.reserve(n_vertices());
  for (Vertex v : vertices()) {
    std::uint64_t code = 0;
    for (int k = 0; k < 3; ++k) {
      const double extent = hi[k] - lo[k];
      const double t = extent > 0 ? (position(v)[k] - lo[k]) / extent : 0.0;
      code |= spread_bits(static_cast<std::uint64_t>(std::clamp(t, 0.0, 1.0) * 2097151.0)) << k;
    }
    keyed.push_back({code, v.idx});
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<Index> vkeep(keyed.size()), rank(vertices_size(), kInvalidIndex);
  for (size_t i = 0; i < keyed.size(); ++i) {
    vkeep[i] = keyed[i].second;
    rank[keyed[i].second] = static_cast<Index>(i);
  }
  // Edges and faces by the rank of their first vertex in that order (then by slot).
  std::vector<std::pair<Index, Index>> by_rank;
  by_rank.reserve(n_edges());
  for (Edge e : edges())
    by_rank.push_back({std::min(rank[to_vertex(halfedge(e, 0)).idx], rank[to_vertex(halfedge(e, 1)).idx]), e.idx});
  std::sort(by_rank.begin(), by_rank.end());
  std::vector<Index> ekeep;
  ekeep.reserve(by_rank.size());
  for (const auto& [r, e] : by_rank) ekeep.push_back(e);
  by_rank.clear();
  for (Face f : faces()) {
    Vertex c[3];
    face_vertices(f, c);
    by_rank.push_back({std::min({rank[c[0].idx], rank[c[1].idx], rank[c[2].idx]}), f.idx});
  }
  std::sort(by_rank.begin(), by_rank.end());
  std::vector<Index> fkeep;
  fkeep.reserve(by_rank.size());
  for (const auto& [r, f] : by_rank) fkeep.push_back(f);
  compact_to(vkeep, ekeep, fkeep);
}

void SurfaceMesh::compact_to(const std::vector<Index>& vkeep, const std::vector<Index>& ekeep,
                             const std::vector<Index>& fkeep) {
  const size_t nv = vertices_size(), ne = edges_size(), nf = faces_size();
  std::vector<Index> vmap(nv, kInvalidIndex), hmap(2 * ne, kInvalidIndex), fmap(nf, kInvalidIndex);
  std::vector<Index> hkeep;
  hkeep.reserve(2 * ekeep.size());
  for (size_t i = 0; i < vkeep.size(); ++i) vmap[vkeep[i]] = static_cast<Index>(i);
  for (size_t i = 0; i < ekeep.size(); ++i) {
    const Index e = ekeep[i], ni = static_cast<Index>(i);
    hmap[2 * e] = 2 * ni;
    hmap[2 * e + 1] = 2 * ni + 1;
    hkeep.push_back(2 * e);
    hkeep.push_back(2 * e + 1);
  }
  for (size_t i = 0; i < fkeep.size(); ++i) fmap[fkeep[i]] = static_cast<Index>(i);

  auto remap_h = [&](Halfedge h) { return h.is_valid() ? Halfedge(hmap[h.idx]) : h; };
  for (Index i : vkeep) vconn_[Vertex(i)] = remap_h(vconn_[Vertex(i)]);
  for (Index i : hkeep) {
    auto& c = hconn_[Halfedge(i)];
    c.to = Vertex(vmap[c.to.idx]);
    c.next = remap_h(c.next);
    c.prev = remap_h(c.prev);
    if (c.face.is_valid()) c.face = Face(fmap[c.face.idx]);
  }
  for (Index i : fkeep) fconn_[Face(i)] = remap_h(fconn_[Face(i)]);

  vprops_.compact(vkeep);
  hprops_.compact(hkeep);
  eprops_.compact(ekeep);
  fprops_.compact(fkeep);
  deleted_vertices_ = deleted_edges_ = deleted_faces_ = 0;
}

namespace {
[[noreturn]] void fail(const std::string& what) { throw std::logic_error("invalid mesh: " + what); }
std::string name(const char* kind, Index i) { return std::string(kind) + " " + std::to_string(i); }
}  // namespace

void SurfaceMesh::validate() const {
  const Index nv = static_cast<Index>(vertices_size()), nh = static_cast<Index>(halfedges_size()),
              nf = static_cast<Index>(faces_size());
  size_t live_v = 0, live_e = 0, live_f = 0;
  for (Index i = 0; i < nv; ++i) live_v += !vdeleted_[Vertex(i)];
  for (Index i = 0; i < edges_size(); ++i) live_e += !edeleted_[Edge(i)];
  for (Index i = 0; i < nf; ++i) live_f += !fdeleted_[Face(i)];
  if (live_v != n_vertices() || live_e != n_edges() || live_f != n_faces()) fail("deletion counters out of date");

  for (Index i = 0; i < nh; ++i) {
    Halfedge h(i);
    if (is_deleted(h)) continue;
    // Names are built only on failure: validate() runs on every loaded mesh.
    auto hn = [i] { return name("halfedge", i); };
    Vertex to = to_vertex(h);
    if (!to.is_valid() || to.idx >= nv || is_deleted(to)) fail(hn() + " points to a missing vertex");
    Halfedge n = next(h), p = prev(h);
    if (!n.is_valid() || n.idx >= nh || is_deleted(n)) fail(hn() + " has a missing next");
    if (!p.is_valid() || p.idx >= nh || is_deleted(p)) fail(hn() + " has a missing prev");
    if (prev(n) != h || next(p) != h) fail(hn() + ": next/prev disagree");
    if (n == h) fail(hn() + " is its own next");
    if (from_vertex(n) != to) fail(hn() + ": next does not start where it ends");
    if (to == from_vertex(h)) fail(hn() + " is a loop");
    Face f = face(h);
    if (f.is_valid() && (f.idx >= nf || is_deleted(f))) fail(hn() + " refers to a deleted face");
    if (face(n) != f) fail(hn() + ": next lies in another face");
    if (is_boundary(h) && is_boundary(opposite(h))) fail(hn() + ": edge has no face on either side");
  }
  for (Index i = 0; i < nf; ++i) {
    Face f(i);
    if (is_deleted(f)) continue;
    Halfedge h = halfedge(f);
    if (!h.is_valid() || h.idx >= nh || is_deleted(h) || face(h) != f) fail(name("face", i) + " has a bad halfedge");
    if (next(next(next(h))) != h) fail(name("face", i) + " is not a triangle");
  }

  // Per vertex: one fan (manifold), the boundary invariant, no duplicate edges.
  std::vector<Index> outgoing_count(nv, 0);
  for (Index i = 0; i < nh; ++i)
    if (!is_deleted(Halfedge(i))) ++outgoing_count[from_vertex(Halfedge(i)).idx];
  std::vector<Index> seen_mark(nv, kInvalidIndex);
  for (Index i = 0; i < nv; ++i) {
    Vertex v(i);
    if (is_deleted(v)) continue;
    auto vn = [i] { return name("vertex", i); };
    Halfedge start = halfedge(v);
    if (!start.is_valid()) {
      if (outgoing_count[i]) fail(vn() + " has edges but no halfedge");
      continue;
    }
    if (start.idx >= nh || is_deleted(start) || from_vertex(start) != v) fail(vn() + ": halfedge is not outgoing");
    Index count = 0, boundary = 0;
    Halfedge h = start;
    do {
      if (from_vertex(h) != v) fail(vn() + ": rotation leaves the vertex");
      Vertex w = to_vertex(h);
      if (seen_mark[w.idx] == i) fail(vn() + " has two edges to vertex " + std::to_string(w.idx));
      seen_mark[w.idx] = i;
      boundary += is_boundary(h);
      if (++count > outgoing_count[i]) fail(vn() + ": rotation does not close");
      h = cw_rotated(h);
    } while (h != start);
    if (count != outgoing_count[i]) fail(vn() + " is non-manifold (more than one fan)");
    if (boundary > 1) fail(vn() + " lies on the boundary twice");
    if (boundary == 1 && !is_boundary(start)) fail(vn() + ": boundary vertex without boundary halfedge");
  }
}

}  // namespace adasculpt::mesh
