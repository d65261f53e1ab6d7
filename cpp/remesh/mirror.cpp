// Mirror symmetry for region iterations (Remesher::enable_mirror): each operation is decided
// once, on whichever edge of a mirror pair the pass meets first, and done on both. Decisions
// are never taken twice because the two sides' floating-point values differ in the last bits
// (a reflected triangle is walked in the opposite order), and a threshold test could go either
// way on each side; positions and sizes of one side are copied, mirrored, to the other.
#include <algorithm>

#include "geometry/mirror_symmetry.h"
#include "remesh/remesher_impl.h"

namespace adasculpt::remesh {

bool Remesher::enable_mirror(int axis) {
  Impl& m = *impl_;
  std::vector<Vertex> kept = std::move(m.kept_mirror);
  const bool reuse = m.kept_mirror_axis == axis && kept.size() == m.mesh.vertices_size() &&
                     !(m.opt.feature_angle_deg > 0) && !mesh::find_mask(m.mesh).is_valid();
  disable_mirror();
  if (reuse) {  // the last stroke's map (disable_mirror(true)): no search, no pass over the mesh
    m.mirror = m.mesh.vertex_property<Vertex>("remesh:mirror", Vertex());
    m.mirror.vector() = std::move(kept);
    m.mirror_axis = axis;
    return true;
  }
  std::vector<Vertex> image = geometry::find_mirror_map(m.mesh, axis);
  if (image.empty()) return false;
  // A mask that is not its own mirror image would stop one side of a pair and not the other.
  if (const mesh::VertexProperty<float> mask = mesh::find_mask(m.mesh); mask.is_valid())
    for (Vertex v : m.mesh.vertices())
      if (mask[v] != mask[image[v.idx]]) return false;
  m.mirror = m.mesh.vertex_property<Vertex>("remesh:mirror", Vertex());
  m.mirror.vector() = std::move(image);
  m.mirror_axis = axis;
  // Feature flags and sizes come from dihedral angles and curvature, computed per side: make the
  // pairs agree (an edge is a feature when either side says so). Only feature edges need their
  // image looked up; the connectivity elsewhere is checked edge by edge as the passes go. The
  // marks added are listed: disable_mirror takes them back, so that a kept remesher's marks stay
  // those a new one would give (reset_slots).
  for (Edge e : m.mesh.edges()) {
    if (!m.feature[e]) continue;
    const Edge img = m.mirror_edge(e);
    if (!img.is_valid()) {
      disable_mirror();
      return false;
    }
    if (!m.feature[img]) m.mirror_marked.push_back(img);
    m.feature[img] = 1;
  }
  for (Vertex v : m.mesh.vertices()) {
    const Vertex w = m.mirror[v];
    if (v.idx < w.idx) m.sizing[w] = m.sizing[v];
  }
  return true;
}

void Remesher::disable_mirror(bool keep_map) {
  Impl& m = *impl_;
  m.kept_mirror.clear();
  m.kept_mirror_axis = -1;
  if (keep_map && m.mirror_axis >= 0 && m.mirror.is_valid()) {
    m.kept_mirror = std::move(m.mirror.vector());
    m.kept_mirror_axis = m.mirror_axis;
  }
  m.mirror_axis = -1;
  // (An edge the passes split or removed since is around the stroke's touched vertices: the
  // caller's reset_slots marks it again.)
  for (Edge e : m.mirror_marked)
    if (e.idx < m.mesh.edges_size()) m.feature[e] = 0;
  m.mirror_marked.clear();
  if (m.mirror.is_valid()) m.mesh.remove_vertex_property(m.mirror);
}

const std::vector<Vertex>* Remesher::mirror_map() const {
  return impl_->mirror_axis >= 0 ? &impl_->mirror.vector() : nullptr;
}

void Remesher::Impl::stop_mirroring() { mirror_axis = -1; }

Edge Remesher::Impl::mirror_edge(Edge e) {
  const Vertex a = mirror[mesh.vertex(e, 0)], b = mirror[mesh.vertex(e, 1)];
  const Halfedge h = a.is_valid() && b.is_valid() ? mesh.find_halfedge(a, b) : Halfedge();
  if (!h.is_valid()) {
    stop_mirroring();
    return Edge();
  }
  return mesh.edge(h);
}

bool Remesher::Impl::overlaps_its_image(Vertex a, Vertex b) {
  near_scratch.clear();
  for (Vertex c : {a, b}) {
    near_scratch.push_back(c);
    for (Vertex w : mesh.vertices(c)) near_scratch.push_back(w);
  }
  for (Vertex v : near_scratch)
    if (std::find(near_scratch.begin(), near_scratch.end(), mirror[v]) != near_scratch.end()) return true;
  return false;
}

Edge Remesher::Impl::flip_partner(Edge e) {
  if (mirror_axis < 0) return e;
  const Edge img = mirror_edge(e);
  if (!img.is_valid() || img == e) return img;
  const Halfedge h = mesh.halfedge(e, 0), o = mesh.halfedge(e, 1);
  const Vertex quad[4] = {mesh.to_vertex(h), mesh.to_vertex(o), mesh.to_vertex(mesh.next(h)),
                          mesh.to_vertex(mesh.next(o))};
  for (Vertex v : quad)
    if (std::find(quad, quad + 4, mirror[v]) != quad + 4) return Edge();
  return img;
}

size_t Remesher::Impl::collapse_with_mirror(Halfedge h, bool midpoint) {
  if (mirror_axis < 0) {
    apply_collapse(h, midpoint);
    return 1;
  }
  const Vertex v0 = mesh.from_vertex(h), v1 = mesh.to_vertex(h);
  const Vertex m0 = mirror[v0], m1 = mirror[v1];
  if (m0 == v1) {
    // Across the plane: only meeting in the middle, which is on the plane, keeps the symmetry.
    if (!midpoint) {
      if (!movable(v0) || !movable(v1) || vclass[v0] != kFree || vclass[v1] != kFree) return 0;
      const Point mid = 0.5 * (mesh.position(v0) + mesh.position(v1));
      if (!collapse_geometry_ok(h, mid, true) || !collapse_topology_ok(h) || collapse_crosses(h, mid, true)) return 0;
    }
    apply_collapse(h, true);
    mirror[v1] = v1;
    return 1;
  }
  if (m0 == v0 && m1 == v1) {  // in the plane: its own image
    apply_collapse(h, midpoint);
    return 1;
  }
  const Halfedge g = mesh.find_halfedge(m0, m1);
  if (!g.is_valid()) {
    stop_mirroring();
    apply_collapse(h, midpoint);
    return 1;
  }
  // Disjoint neighbourhoods: the first collapse changes nothing the second one's checks read, so
  // the image, valid before, is still valid after.
  if (overlaps_its_image(v0, v1) || !collapse_topology_ok(g)) return 0;
  apply_collapse(h, midpoint);
  apply_collapse(g, midpoint);
  return 2;
}

void Remesher::Impl::close_region_under_mirror(std::vector<Vertex>& region) {
  const size_t n = region.size();
  for (size_t i = 0; i < n; ++i) {
    const Vertex v = region[i];
    if (mesh.is_deleted(v)) continue;
    const Vertex w = mirror[v];
    if (!w.is_valid()) {
      stop_mirroring();
      return;
    }
    if (w != v) region.push_back(w);  // duplicates are skipped by the scope marks
  }
}

void Remesher::Impl::symmetrize_sizing(const std::vector<Vertex>& vertices) {
  for (Vertex v : vertices) {
    if (mesh.is_deleted(v)) continue;
    const Vertex w = mirror[v];
    if (w.is_valid() && v.idx < w.idx) sizing[w] = sizing[v];
  }
}

void Remesher::Impl::symmetrize_positions() {
  for (Vertex v : scope_vertices) {
    if (mesh.is_deleted(v) || !movable(v)) continue;
    const Vertex w = mirror[v];
    if (w == v)
      mesh.position(v)[mirror_axis] = 0;
    else if (w.is_valid() && v.idx < w.idx)
      mesh.position(w) = mirrored(mesh.position(v));
  }
}

}  // namespace adasculpt::remesh
