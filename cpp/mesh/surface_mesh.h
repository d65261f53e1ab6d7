#pragma once
// SurfaceMesh: a halfedge data structure for manifold triangle meshes (with boundaries).
//
// Halfedges are stored in pairs: halfedge 2e and 2e+1 are the two sides of edge e, so the
// opposite of a halfedge is found by flipping the lowest bit. A boundary halfedge has no face.
// Invariant kept by every operation: a boundary vertex's outgoing halfedge is a boundary
// halfedge, so is_boundary(v) is O(1).
//
// Deleting elements only marks them; garbage_collection() compacts the arrays. Handles are
// stable until then. Attach per-element data with add_*_property.
#include <cstdint>
#include <string>
#include <vector>

#include "mesh/handles.h"
#include "mesh/properties.h"
#include "mesh/types.h"

namespace adasculpt::mesh {

class SurfaceMesh {
 public:
  SurfaceMesh();
  SurfaceMesh(const SurfaceMesh& other);
  SurfaceMesh& operator=(const SurfaceMesh& other);
  SurfaceMesh(SurfaceMesh&& other) noexcept;
  SurfaceMesh& operator=(SurfaceMesh&& other) noexcept;
  ~SurfaceMesh() = default;

  // ---- sizes: n_* counts live elements, *_size counts array slots including deleted ones
  size_t n_vertices() const { return vertices_size() - deleted_vertices_; }
  size_t n_halfedges() const { return halfedges_size() - 2 * deleted_edges_; }
  size_t n_edges() const { return edges_size() - deleted_edges_; }
  size_t n_faces() const { return faces_size() - deleted_faces_; }
  size_t vertices_size() const { return vprops_.size(); }
  size_t halfedges_size() const { return hprops_.size(); }
  size_t edges_size() const { return eprops_.size(); }
  size_t faces_size() const { return fprops_.size(); }
  bool is_empty() const { return n_vertices() == 0; }
  bool has_garbage() const { return deleted_vertices_ + deleted_edges_ + deleted_faces_ > 0; }
  void clear();
  void reserve(size_t vertices, size_t edges, size_t faces);
  // Room for an eighth more of every element than the arrays hold: the first strokes on a mesh
  // just restored from history (a copy, whose arrays are exactly full) then add elements without
  // copying every array in the middle of a frame.
  void reserve_room_for_edits();

  // ---- low-level construction (used by the soup builder and by edits)
  Vertex add_vertex(const Point& p);
  Halfedge new_edge(Vertex from, Vertex to);  // two unlinked halfedges, from->to is returned
  Face new_face();

  // ---- connectivity
  Halfedge halfedge(Vertex v) const { return vconn_[v]; }
  void set_halfedge(Vertex v, Halfedge h) { vconn_[v] = h; }
  Vertex to_vertex(Halfedge h) const { return hconn_[h].to; }
  Vertex from_vertex(Halfedge h) const { return to_vertex(opposite(h)); }
  void set_vertex(Halfedge h, Vertex v) { hconn_[h].to = v; }
  Halfedge next(Halfedge h) const { return hconn_[h].next; }
  Halfedge prev(Halfedge h) const { return hconn_[h].prev; }
  void set_next(Halfedge h, Halfedge n) {
    hconn_[h].next = n;
    hconn_[n].prev = h;
  }
  static Halfedge opposite(Halfedge h) { return Halfedge(h.idx ^ 1u); }
  static Edge edge(Halfedge h) { return Edge(h.idx >> 1); }
  static Halfedge halfedge(Edge e, unsigned i) { return Halfedge((e.idx << 1) | i); }
  Face face(Halfedge h) const { return hconn_[h].face; }
  void set_face(Halfedge h, Face f) { hconn_[h].face = f; }
  Halfedge halfedge(Face f) const { return fconn_[f]; }
  void set_halfedge(Face f, Halfedge h) { fconn_[f] = h; }
  Vertex vertex(Edge e, unsigned i) const { return to_vertex(halfedge(e, i)); }
  // Next outgoing halfedge around from_vertex(h) (counter-clockwise seen from outside).
  Halfedge ccw_rotated(Halfedge h) const { return opposite(prev(h)); }
  Halfedge cw_rotated(Halfedge h) const { return next(opposite(h)); }

  bool is_boundary(Halfedge h) const { return !face(h).is_valid(); }
  bool is_boundary(Edge e) const { return is_boundary(halfedge(e, 0)) || is_boundary(halfedge(e, 1)); }
  bool is_boundary(Vertex v) const {
    Halfedge h = halfedge(v);
    return !h.is_valid() || is_boundary(h);
  }
  bool is_boundary(Face f) const;  // any of its edges on the boundary
  bool is_isolated(Vertex v) const { return !halfedge(v).is_valid(); }
  size_t valence(Vertex v) const;
  // The halfedge from a to b, or an invalid handle.
  Halfedge find_halfedge(Vertex a, Vertex b) const;
  // The three vertices of a triangle, starting at to_vertex(halfedge(f)). Inline: whole-mesh
  // scans (picking, render buffers, quality) call it once per face.
  void face_vertices(Face f, Vertex out[3]) const {
    const HalfedgeConnectivity* hc = hconn_.vector().data();
    const HalfedgeConnectivity& c0 = hc[halfedge(f).idx];
    const HalfedgeConnectivity& c1 = hc[c0.next.idx];
    out[0] = c0.to;
    out[1] = c1.to;
    out[2] = hc[c1.next.idx].to;
  }

  // ---- deletion marks
  bool is_deleted(Vertex v) const { return vdeleted_[v] != 0; }
  bool is_deleted(Halfedge h) const { return edeleted_[edge(h)] != 0; }
  bool is_deleted(Edge e) const { return edeleted_[e] != 0; }
  bool is_deleted(Face f) const { return fdeleted_[f] != 0; }
  void delete_vertex_mark(Vertex v);
  void delete_edge_mark(Edge e);
  void delete_face_mark(Face f);
  // Compacts all arrays; every handle held outside the mesh becomes meaningless.
  void garbage_collection();
  // Compacts all arrays as garbage_collection does, and puts the vertices in the order of a
  // Z-order (Morton) curve through the bounding box, the edges and faces in the order of their
  // first vertex in it: neighbours on the surface then lie near each other in memory. Splits
  // append their elements at the end, so a remeshed surface's fans are scattered over the arrays,
  // and every walk around a fan missed the cache at each step: a grab's frames on the held-out
  // 100k scan took 10.1 ms (median) remeshed, 6.1 ms sorted. Handles become meaningless.
  void sort_in_space();

  // ---- positions
  const Point& position(Vertex v) const { return points_[v]; }
  Point& position(Vertex v) { return points_[v]; }
  std::vector<Point>& positions() { return points_.vector(); }
  const std::vector<Point>& positions() const { return points_.vector(); }

  // ---- flat views for hot loops: raw arrays indexed by handle index, valid until an element is
  // added (split, add_vertex, new_edge, new_face); collapse, flip and deletion keep them valid.
  struct HalfedgeConnectivity {
    Vertex to;
    Halfedge next, prev;
    Face face;
  };
  const HalfedgeConnectivity* halfedge_connectivity_data() const { return hconn_.vector().data(); }
  const Halfedge* vertex_halfedge_data() const { return vconn_.vector().data(); }
  const Halfedge* face_halfedge_data() const { return fconn_.vector().data(); }
  const std::uint8_t* vertex_deleted_data() const { return vdeleted_.vector().data(); }
  const std::uint8_t* edge_deleted_data() const { return edeleted_.vector().data(); }
  const std::uint8_t* face_deleted_data() const { return fdeleted_.vector().data(); }

  // ---- topological edits (triangle meshes). Geometric checks are the caller's business.
  // Inserts a vertex at p on edge e and splits the one or two incident triangles.
  // Returns the new vertex; its outgoing halfedge(v) runs along the old edge towards the
  // old to_vertex(halfedge(e,0)).
  Vertex split(Edge e, const Point& p);
  // Link condition and boundary rules: true when collapsing h keeps the mesh a manifold.
  bool is_collapse_ok(Halfedge h) const;
  // Removes from_vertex(h), moving its connections to to_vertex(h) (which keeps its position).
  // Of the two triangles that vanish, the edges of prev(h) and next(opposite(h)) survive; the
  // edges of next(h) and prev(opposite(h)) are deleted (callers carrying edge data rely on it).
  void collapse(Halfedge h);
  bool is_flip_ok(Edge e) const;
  // Replaces the diagonal of the quad formed by the two triangles of e. The two faces keep
  // their slots: with halfedge(e,0) = a->b in (a, b, c) and halfedge(e,1) in (b, a, d), the first
  // face becomes (a, d, c) and the second (d, b, c).
  void flip(Edge e);

  // ---- raw slot access for the undo log (sculpt/undo_log.h), which copies slots byte for byte and
  // truncates or regrows the arrays; it keeps the deletion counters in step with the flags.
  PropertyContainer& vertex_properties() { return vprops_; }
  PropertyContainer& halfedge_properties() { return hprops_; }
  PropertyContainer& edge_properties() { return eprops_; }
  PropertyContainer& face_properties() { return fprops_; }
  struct DeletedCounts {
    size_t vertices = 0, edges = 0, faces = 0;
  };
  DeletedCounts deleted_counts() const { return {deleted_vertices_, deleted_edges_, deleted_faces_}; }
  void set_deleted_counts(const DeletedCounts& c) {
    deleted_vertices_ = c.vertices;
    deleted_edges_ = c.edges;
    deleted_faces_ = c.faces;
  }

  // Throws std::logic_error describing the first broken connectivity invariant.
  void validate() const;

  // ---- properties
  template <class T>
  VertexProperty<T> add_vertex_property(const std::string& name, T def = T()) {
    return VertexProperty<T>(vprops_.add<T>(name, std::move(def)));
  }
  template <class T>
  VertexProperty<T> adopt_vertex_property(const std::string& name, std::vector<T>&& data, T def = T()) {
    return VertexProperty<T>(vprops_.adopt<T>(name, std::move(data), std::move(def)));
  }
  template <class T>
  VertexProperty<T> get_vertex_property(const std::string& name) const {
    return VertexProperty<T>(vprops_.get<T>(name));
  }
  template <class T>
  VertexProperty<T> vertex_property(const std::string& name, T def = T()) {
    auto p = get_vertex_property<T>(name);
    return p.is_valid() ? p : add_vertex_property<T>(name, std::move(def));
  }
  template <class T>
  void remove_vertex_property(VertexProperty<T>& p) {
    vprops_.remove(p.array());
    p = VertexProperty<T>();
  }
  template <class T>
  HalfedgeProperty<T> add_halfedge_property(const std::string& name, T def = T()) {
    return HalfedgeProperty<T>(hprops_.add<T>(name, std::move(def)));
  }
  template <class T>
  HalfedgeProperty<T> get_halfedge_property(const std::string& name) const {
    return HalfedgeProperty<T>(hprops_.get<T>(name));
  }
  template <class T>
  EdgeProperty<T> add_edge_property(const std::string& name, T def = T()) {
    return EdgeProperty<T>(eprops_.add<T>(name, std::move(def)));
  }
  template <class T>
  EdgeProperty<T> get_edge_property(const std::string& name) const {
    return EdgeProperty<T>(eprops_.get<T>(name));
  }
  template <class T>
  EdgeProperty<T> edge_property(const std::string& name, T def = T()) {
    auto p = get_edge_property<T>(name);
    return p.is_valid() ? p : add_edge_property<T>(name, std::move(def));
  }
  template <class T>
  void remove_edge_property(EdgeProperty<T>& p) {
    eprops_.remove(p.array());
    p = EdgeProperty<T>();
  }
  template <class T>
  FaceProperty<T> add_face_property(const std::string& name, T def = T()) {
    return FaceProperty<T>(fprops_.add<T>(name, std::move(def)));
  }
  template <class T>
  FaceProperty<T> get_face_property(const std::string& name) const {
    return FaceProperty<T>(fprops_.get<T>(name));
  }
  template <class T>
  FaceProperty<T> face_property(const std::string& name, T def = T()) {
    auto p = get_face_property<T>(name);
    return p.is_valid() ? p : add_face_property<T>(name, std::move(def));
  }
  template <class T>
  void remove_face_property(FaceProperty<T>& p) {
    fprops_.remove(p.array());
    p = FaceProperty<T>();
  }

  // ---- iteration over live elements: for (Vertex v : mesh.vertices()) ...
  template <class H>
  class ElementIterator {
   public:
    ElementIterator(const SurfaceMesh* m, Index i, Index end) : m_(m), i_(i), end_(end) { skip(); }
    H operator*() const { return H(i_); }
    ElementIterator& operator++() {
      ++i_;
      skip();
      return *this;
    }
    bool operator!=(const ElementIterator& o) const { return i_ != o.i_; }
    bool operator==(const ElementIterator& o) const { return i_ == o.i_; }

   private:
    void skip() {
      while (i_ < end_ && m_->is_deleted(H(i_))) ++i_;
    }
    const SurfaceMesh* m_;
    Index i_, end_;
  };
  template <class H>
  struct ElementRange {
    ElementIterator<H> b, e;
    ElementIterator<H> begin() const { return b; }
    ElementIterator<H> end() const { return e; }
  };
  template <class H>
  ElementRange<H> range(size_t n) const {
    Index end = static_cast<Index>(n);
    return {ElementIterator<H>(this, 0, end), ElementIterator<H>(this, end, end)};
  }
  ElementRange<Vertex> vertices() const { return range<Vertex>(vertices_size()); }
  ElementRange<Halfedge> halfedges() const { return range<Halfedge>(halfedges_size()); }
  ElementRange<Edge> edges() const { return range<Edge>(edges_size()); }
  ElementRange<Face> faces() const { return range<Face>(faces_size()); }

  // ---- circulators
  // Outgoing halfedges of a vertex; Value maps each halfedge to what is reported.
  template <class Value>
  class VertexCirculator {
   public:
    // Only compares against end(): the walk is over once it is back at its start halfedge.
    VertexCirculator(const SurfaceMesh* m, Halfedge start, bool done)
        : m_(m), h_(start), start_(start), done_(done || !start.is_valid()) {
      skip();
    }
    auto operator*() const { return Value::get(*m_, h_); }
    VertexCirculator& operator++() {
      step();
      skip();
      return *this;
    }
    bool operator!=(const VertexCirculator& o) const { return done_ != o.done_; }

   private:
    void step() {
      h_ = m_->cw_rotated(h_);
      if (h_ == start_) done_ = true;
    }
    void skip() {
      while (!done_ && !Value::valid(*m_, h_)) step();
    }
    const SurfaceMesh* m_;
    Halfedge h_, start_;
    bool done_;
  };
  struct OutgoingHalfedge {
    static Halfedge get(const SurfaceMesh&, Halfedge h) { return h; }
    static bool valid(const SurfaceMesh&, Halfedge) { return true; }
  };
  struct NeighbourVertex {
    static Vertex get(const SurfaceMesh& m, Halfedge h) { return m.to_vertex(h); }
    static bool valid(const SurfaceMesh&, Halfedge) { return true; }
  };
  struct IncidentFace {
    static Face get(const SurfaceMesh& m, Halfedge h) { return m.face(h); }
    static bool valid(const SurfaceMesh& m, Halfedge h) { return m.face(h).is_valid(); }
  };
  template <class Value>
  struct CirculatorRange {
    const SurfaceMesh* m;
    Halfedge start;
    VertexCirculator<Value> begin() const { return VertexCirculator<Value>(m, start, false); }
    VertexCirculator<Value> end() const { return VertexCirculator<Value>(m, start, true); }
  };
  CirculatorRange<OutgoingHalfedge> halfedges(Vertex v) const { return {this, halfedge(v)}; }
  CirculatorRange<NeighbourVertex> vertices(Vertex v) const { return {this, halfedge(v)}; }
  CirculatorRange<IncidentFace> faces(Vertex v) const { return {this, halfedge(v)}; }

  // Halfedges of a face (three for a triangle).
  class FaceHalfedgeIterator {
   public:
    FaceHalfedgeIterator(const SurfaceMesh* m, Halfedge h, bool active) : m_(m), h_(h), start_(h), active_(active) {}
    Halfedge operator*() const { return h_; }
    FaceHalfedgeIterator& operator++() {
      h_ = m_->next(h_);
      active_ = true;
      return *this;
    }
    bool operator!=(const FaceHalfedgeIterator& o) const { return h_ != o.h_ || active_ != o.active_; }

   private:
    const SurfaceMesh* m_;
    Halfedge h_, start_;
    bool active_;
  };
  struct FaceHalfedgeRange {
    const SurfaceMesh* m;
    Halfedge start;
    FaceHalfedgeIterator begin() const { return FaceHalfedgeIterator(m, start, false); }
    FaceHalfedgeIterator end() const { return FaceHalfedgeIterator(m, start, true); }
  };
  FaceHalfedgeRange halfedges(Face f) const { return {this, halfedge(f)}; }

 private:
  void bind_builtin_properties();
  // The live elements, new element i being old slot keep[i] (edges: both halfedges, in order);
  // every connectivity reference is renumbered.
  void compact_to(const std::vector<Index>& vkeep, const std::vector<Index>& ekeep, const std::vector<Index>& fkeep);
  void remove_loop_after_collapse(Halfedge keep, Halfedge remove);
  void fix_outgoing_halfedge(Vertex v);

  PropertyContainer vprops_, hprops_, eprops_, fprops_;
  VertexProperty<Point> points_;
  VertexProperty<Halfedge> vconn_;
  HalfedgeProperty<HalfedgeConnectivity> hconn_;
  FaceProperty<Halfedge> fconn_;
  VertexProperty<std::uint8_t> vdeleted_;
  EdgeProperty<std::uint8_t> edeleted_;
  FaceProperty<std::uint8_t> fdeleted_;
  size_t deleted_vertices_ = 0, deleted_edges_ = 0, deleted_faces_ = 0;
};

}  // namespace adasculpt::mesh
