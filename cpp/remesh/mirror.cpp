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
  disable_mirror();
  std::vector<Vertex> image = geometry::find_mirror_map(impl_->mesh, axis);
  return !image.empty() && impl_->start_mirroring(axis, image, false);
}

bool Remesher::enable_mirror(int axis, std::vector<Vertex>& known_map) {
  disable_mirror();
  if (known_map.size() != impl_->mesh.vertices_size()) return false;
  // Between strokes every sizing is 0 (reset_slots), so the pairs already agree on it; the lender
  // vouches for the mask.
  return impl_->start_mirroring(axis, known_map, true);
}

bool Remesher::Impl::start_mirroring(int axis, std::vector<Vertex>& image, bool lent) {
  // A mask that is not its own mirror image would stop one side of a pair and not the other (a
  // lender checked it: geometry::MirrorTracker::mask_symmetric).
  if (const mesh::VertexProperty<float> mask = mesh::find_mask(mesh); mask.is_valid() && !lent)
    for (Vertex v : mesh.vertices())
      if (mask[v] != mask[image[v.idx]]) return false;
  mirror = mesh.adopt_vertex_property<Vertex>("remesh:mirror", std::move(image), Vertex());
  mirror_axis = axis;
  mirror_lent = lent;
  // Feature flags and sizes come from dihedral angles and curvature, computed per side: make the
  // pairs agree (an edge is a feature when either side says so). Only feature edges need their
  // image looked up; the connectivity elsewhere is checked edge by edge as the passes go. The
  // marks added are listed: disable_mirror takes them back, so that a kept remesher's marks stay
  // those a new one would give (reset_slots). With features off the marks are the boundary's,
  // which a symmetric mesh's pairs share: no pass.
  if (opt.feature_angle_deg > 0 && !union_mirror_features(lent)) {
    if (lent) image = std::move(mirror.vector());  // back to the lender, as it was
    mirror_lent = false;
    remove_mirror();
    return false;
  }
  if (!lent)
    for (Vertex v : mesh.vertices()) {
      const Vertex w = mirror[v];
      if (v.idx < w.idx) sizing[w] = sizing[v];
    }
  return true;
}

void Remesher::note_mirror_changes(const std::vector<Vertex>& changed) {
  Impl& m = *impl_;
  if (!m.mirror_pairs_known) return;  // the next check reads every edge anyway
  const size_t n = m.mesh.vertices_size();
  mesh::resize_scratch(m.mirror_seen, n, 0u);
  for (Vertex v : changed) {
    if (v.idx >= n || m.mirror_seen[v.idx] == m.mirror_run) continue;  // (slots an undo cut off: gone)
    m.mirror_seen[v.idx] = m.mirror_run;
    m.mirror_changed.push_back(v);
  }
  // Past an eighth of the mesh, reading every edge costs about what the rings would.
  if (m.mirror_changed.size() > n / 8 + 64) m.forget_mirror_pairs();
}

const std::vector<Edge>* Remesher::mirror_unpaired_features() const {
  return impl_->mirror_pairs_known ? &impl_->mirror_unpaired : nullptr;
}

void Remesher::Impl::forget_mirror_pairs() {
  mirror_pairs_known = false;
  mirror_changed.clear();
  mirror_unpaired.clear();
  next_mirror_run();
}

void Remesher::Impl::next_mirror_run() {
  if (++mirror_run == 0) {
    std::fill(mirror_seen.begin(), mirror_seen.end(), 0u);
    mirror_run = 1;
  }
}

// An edge is unpaired when it is a feature and its image is not (or is no edge). Whether it is
// depends on its own mark, its ends' images, the edge between those and that edge's mark. Since the
// last check, marks changed only on edges with both ends within two rings of a changed slot C
// (reset_slots derives them again on the faces around C's first ring), edges and positions only at
// C, and the image of a slot outside C only when its old image is in C, so that its new one is too
// (the one vertex at its mirror position moved there). So an edge whose state changed has an end
// in R = the two rings of C, or an end whose image is in R: every unpaired edge is among those
// edges and the ones unpaired at the last check. The answer is the whole pass's, edge for edge.
bool Remesher::Impl::union_mirror_features(bool lent) {
  const auto image_of = [&](Edge e) {
    const Vertex a = mirror[mesh.vertex(e, 0)], b = mirror[mesh.vertex(e, 1)];
    const Halfedge h = a.is_valid() && b.is_valid() ? mesh.find_halfedge(a, b) : Halfedge();
    return h.is_valid() ? mesh.edge(h) : Edge();
  };
  const auto unpaired = [&](Edge e) {
    if (!feature[e]) return false;
    const Edge img = image_of(e);
    return !img.is_valid() || !feature[img];
  };
  std::vector<Edge>& found = mirror_candidates;
  found.clear();
  const bool local = lent && mirror_pairs_known && mirror_pairs_angle == opt.feature_angle_deg &&
                     mirror_pairs_axis == mirror_axis;
  if (local) {
    const size_t n = mesh.vertices_size();
    mesh::resize_scratch(mirror_seen, n, 0u);
    next_mirror_run();
    mirror_ring.clear();
    const auto list = [&](Vertex v) {
      if (mirror_seen[v.idx] == mirror_run) return;
      mirror_seen[v.idx] = mirror_run;
      mirror_ring.push_back(v);
    };
    for (Vertex v : mirror_changed)
      if (v.idx < n && !mesh.is_deleted(v)) list(v);
    for (int ring = 0; ring < 2; ++ring)
      for (size_t i = 0, end = mirror_ring.size(); i < end; ++i)
        for (Vertex w : mesh.vertices(mirror_ring[i])) list(w);
    for (size_t i = 0, end = mirror_ring.size(); i < end; ++i)
      if (const Vertex w = mirror[mirror_ring[i]]; w.is_valid()) list(w);
    for (Vertex v : mirror_ring)
      for (Halfedge h : mesh.halfedges(v))
        if (unpaired(mesh.edge(h))) found.push_back(mesh.edge(h));
    for (Edge e : mirror_unpaired)
      if (e.idx < mesh.edges_size() && !mesh.is_deleted(e) && unpaired(e)) found.push_back(e);
    std::sort(found.begin(), found.end(), [](Edge a, Edge b) { return a.idx < b.idx; });
    found.erase(std::unique(found.begin(), found.end()), found.end());
  } else {
    for (Edge e : mesh.edges())
      if (unpaired(e)) found.push_back(e);
  }
  if (lent) {  // a lender notes its changes (note_mirror_changes); other callers search each time
    mirror_unpaired.assign(found.begin(), found.end());
    mirror_changed.clear();
    next_mirror_run();
    mirror_pairs_known = true;
    mirror_pairs_angle = opt.feature_angle_deg;
    mirror_pairs_axis = mirror_axis;
  }
  for (Edge e : found)
    if (!image_of(e).is_valid()) return false;
  for (Edge e : found) {
    const Edge img = image_of(e);  // distinct edges have distinct images, none of them in `found`
    mirror_marked.push_back(img);
    feature[img] = 1;
  }
  return true;
}

bool Remesher::disable_mirror(std::vector<Vertex>* give_back) {
  Impl& m = *impl_;
  const bool whole = m.mirror_axis >= 0;
  const bool handed_back = give_back && m.mirror_lent && m.mirror.is_valid();
  if (handed_back) *give_back = std::move(m.mirror.vector());
  m.mirror_lent = false;
  m.remove_mirror();
  return whole && handed_back;
}

void Remesher::Impl::remove_mirror() {
  mirror_axis = -1;
  // (An edge the passes split or removed since is around the stroke's touched vertices: the
  // caller's reset_slots marks it again.)
  for (Edge e : mirror_marked)
    if (e.idx < mesh.edges_size()) feature[e] = 0;
  mirror_marked.clear();
  if (mirror.is_valid()) mesh.remove_vertex_property(mirror);
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
