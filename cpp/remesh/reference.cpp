// Reference surface, feature edges and the sizing field of a Remesher.
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "geometry/curvature.h"
#include "geometry/portable_math.h"
#include "geometry/triangle.h"
#include "remesh/remesher_impl.h"
#include "remesh/sizing.h"

namespace adasculpt::remesh {

namespace {
// Closest reference points farther than this many target lengths from a free vertex are
// taken only along the vertex normal (see project()).
constexpr double kFarProjection = 0.25;
// A corner's target length in multiples of the shortest border edge from it to another corner
// (average_feature_sizing): the triangles on that edge get sides of at most 4/3 of the target,
// so their angle at the far corner stays above 2 asin(3 / (8 x 1.5)), 29 degrees.
constexpr double kFixedSegmentSizing = 1.5;
// A hole counts as small when its border is shorter than this many target lengths around it
// (and has at most kSmallHoleEdges edges): target-size edges cannot follow it anyway.
constexpr double kSmallHoleTargets = 2.0;
constexpr int kSmallHoleEdges = 16;
}  // namespace

namespace {
// The scratch buffers of the last remesher destroyed on this thread, lent to the next one.
thread_local RemeshScratch scratch_pool;
}  // namespace

void Remesher::Impl::swap_scratch_with_pool() { std::swap(static_cast<RemeshScratch&>(*this), scratch_pool); }

// The arrays this remesher attached leave the caller's mesh with it: a remeshed mesh carries only
// what it had before. (Removal is by array identity, so a mesh replaced meanwhile loses nothing.)
Remesher::Impl::~Impl() {
  swap_scratch_with_pool();
  mesh.remove_vertex_property(sizing);
  mesh.remove_vertex_property(vclass);
  mesh.remove_vertex_property(scope);
  mesh.remove_vertex_property(ref_hint);
  mesh.remove_vertex_property(segment_hint);
  mesh.remove_vertex_property(anchor);
  mesh.remove_edge_property(feature);
}

Remesher::Impl::Impl(SurfaceMesh& m, const RemeshOptions& o) : mesh(m), opt(o) {
  swap_scratch_with_pool();
  sizing = mesh.vertex_property<double>("remesh:sizing", 0.0);
  vclass = mesh.vertex_property<std::uint8_t>("remesh:class", kFree);
  scope = mesh.vertex_property<std::uint8_t>("remesh:scope", kOutside);
  ref_hint = mesh.vertex_property<std::uint32_t>("remesh:hint", UINT32_MAX);
  segment_hint = mesh.vertex_property<std::uint32_t>("remesh:segment_hint", UINT32_MAX);
  anchor = mesh.vertex_property<std::uint32_t>("remesh:anchor", UINT32_MAX);
  feature = mesh.edge_property<std::uint8_t>("remesh:feature", 0);
  mark_features();
}

void Remesher::Impl::mark_features() {
  if (!(opt.feature_angle_deg > 0)) {
    mark_boundary_edges();
    return;
  }
  const double cos_limit = feature_cos_limit();
  for (Edge e : mesh.edges())
    if (sharp_or_boundary(e, cos_limit)) feature[e] = 1;
  drop_isolated_features();
  // Every vertex's class from feature edges counted at their ends: sequential passes instead of a
  // walk around every fan, which was most of a sculpting stroke's set-up (1.4 ms of WebAssembly on
  // the 35k-vertex bunny, a closed mesh without a single feature edge).
  const std::vector<std::uint8_t> count = feature_edges_per_vertex();
  for (Vertex v : mesh.vertices()) vclass[v] = vertex_class(count[v.idx]);
}

double Remesher::Impl::feature_cos_limit() const {
  return opt.feature_angle_deg > 0 ? portable::cos(opt.feature_angle_deg * M_PI / 180.0) : 2.0;
}

bool Remesher::Impl::sharp_or_boundary(Edge e, double cos_limit) const {
  if (mesh.is_boundary(e)) return true;
  if (!(cos_limit <= 1.0)) return false;  // features off: no dot product is below it
  const Vec3 n0 = geometry::face_normal(mesh, mesh.face(mesh.halfedge(e, 0)));
  const Vec3 n1 = geometry::face_normal(mesh, mesh.face(mesh.halfedge(e, 1)));
  if (glm::dot(n0, n0) == 0.0 || glm::dot(n1, n1) == 0.0) return false;  // degenerate: no angle
  return glm::dot(n0, n1) < cos_limit;
}

// Features off (the sculpting default): the boundary edges are the only feature edges, and any
// other mark a remesher with features on left on this mesh goes. One pass over the edges' faces
// and one over the vertex classes, on the flat arrays, then a fan walk at the boundary's vertices
// only: this runs at the start of every brush stroke, and the general passes above were 9 % of a
// smooth stroke's instructions on the bunny (5.3 M of 62 M, callgrind).
void Remesher::Impl::mark_boundary_edges() {
  const auto* hc = mesh.halfedge_connectivity_data();
  const Halfedge* vh = mesh.vertex_halfedge_data();
  const std::uint8_t* edel = mesh.edge_deleted_data();
  const std::uint8_t* vdel = mesh.vertex_deleted_data();
  std::uint8_t* feat = feature.vector().data();
  std::uint8_t* cls = vclass.vector().data();
  const mesh::Index n_vertices = static_cast<mesh::Index>(mesh.vertices_size());
  for (mesh::Index v = 0; v < n_vertices; ++v)
    if (!vdel[v]) cls[v] = kFree;
  const mesh::Index n_edges = static_cast<mesh::Index>(mesh.edges_size());
  bool any = false;
  for (mesh::Index e = 0; e < n_edges; ++e) {
    if (edel[e]) continue;
    const bool boundary = !hc[e << 1].face.is_valid() || !hc[(e << 1) | 1u].face.is_valid();
    feat[e] = boundary;
    any = any || boundary;
  }
  if (!any) return;
  for (mesh::Index e = 0; e < n_edges; ++e) {
    if (edel[e] || !feat[e]) continue;
    for (unsigned i = 0; i < 2; ++i) {
      const Vertex v = hc[(e << 1) | i].to;
      int count = 0;
      for_each_outgoing(hc, vh, v, [&](Halfedge h) { count += feat[h.idx >> 1] != 0; });
      cls[v.idx] = vertex_class(count);
    }
  }
}

// Sharp edges that belong to no feature line: a lone sharp edge whose ends have no other
// feature edge (a fold of two noisy faces), and the three edges of one face when no other
// feature edge meets its corners (a sliver whose own normal is the outlier: rocker_arm has a
// 7/162/12-degree face whose edges are all "sharp" only against it). Kept, they pin corners
// around edges far shorter than the target length, or make a closed three-edge line that
// relaxation shrinks to a point: rocker_arm --features 45 kept 5-degree triangles there.
std::vector<std::uint8_t> Remesher::Impl::feature_edges_per_vertex() const {
  std::vector<std::uint8_t> count(mesh.vertices_size(), 0);
  for (Edge e : mesh.edges())
    if (is_feature(e))
      for (unsigned i = 0; i < 2; ++i) {
        std::uint8_t& c = count[mesh.vertex(e, i).idx];
        c = static_cast<std::uint8_t>(std::min(c + 1, 255));
      }
  return count;
}

void Remesher::Impl::drop_isolated_features() {
  const std::vector<std::uint8_t> count = feature_edges_per_vertex();
  auto interior_feature = [&](Edge e) { return is_feature(e) && !mesh.is_boundary(e); };
  for (Edge e : mesh.edges())
    if (interior_feature(e) && count[mesh.vertex(e, 0).idx] == 1 && count[mesh.vertex(e, 1).idx] == 1) feature[e] = 0;
  for (mesh::Face f : mesh.faces()) {
    Halfedge h[3] = {mesh.halfedge(f), mesh.next(mesh.halfedge(f)), mesh.prev(mesh.halfedge(f))};
    bool isolated_loop = true;
    for (Halfedge g : h)
      isolated_loop = isolated_loop && interior_feature(mesh.edge(g)) && count[mesh.to_vertex(g).idx] == 2;
    if (isolated_loop)
      for (Halfedge g : h) feature[mesh.edge(g)] = 0;
  }
}

// Sizing at vertices whose surface curvature is not meaningful (feature lines, corners, boundary):
// taken from their free neighbours, not from the sharp edge's huge discrete curvature, so that
// sharp edges are not over-sampled (paper, section 3, feature adjustments).
void Remesher::Impl::average_feature_sizing(const std::vector<Vertex>& vertices) {
  for (Vertex v : vertices) {
    if (vclass[v] == kFree) continue;
    double smallest = opt.max_length;
    int n = 0;
    Vertex ends[2];
    int n_ends = 0;
    double fixed_segment = opt.max_length;
    for (Halfedge h : mesh.halfedges(v)) {
      Vertex w = mesh.to_vertex(h);
      // Only measured neighbours: outside a sculpting frame's region a vertex may never have been
      // (sizing 0). Taking its 0 gave a held feature vertex on the region's border a zero target,
      // every edge at it was split again each frame, and a strip of 0.4 degree slivers grew where the
      // border of a twisted bar's region meets its sharp edges.
      if (vclass[w] == kFree && sizing[w] > 0) {
        smallest = std::min(smallest, sizing[w]);
        ++n;
      }
      if (is_feature(mesh.edge(h)) && n_ends < 2) ends[n_ends++] = w;
      // A border edge between two corners stays as it is (neither end may move or go, and the
      // border is kept): the triangles on it need edges of its length, or they are slivers (a hole
      // of three edges 1e-4 of the diagonal across in cgal/ChineseDragon-10kv left 0.8-degree
      // triangles beside it). Only on a hole smaller than the target (below). Not sharp edges: on
      // a scan with features on, corners sit all along its noisy feature lines, and sizing their
      // short edges down multiplied the vertices by up to 6 with no better angle (the lines meet
      // at tiny angles there themselves). Not the long borders of a CAD model's open panels
      // (cgal/boeing.off: 2.7 times the vertices, more triangles under 20 degrees, some flat).
      if (vclass[v] == kCorner && vclass[w] == kCorner && mesh.is_boundary(mesh.edge(h)))
        fixed_segment = std::min(fixed_segment, glm::length(mesh.position(w) - mesh.position(v)));
    }
    // The paper averages the free neighbours; their minimum keeps the triangles beside a sharp
    // edge as small as the curved side needs (fandisk: Hausdorff 0.210% -> 0.200% of the
    // diagonal for 6% more vertices).
    double size = n ? smallest : opt.max_length;
    if (fixed_segment < opt.max_length && hole_smaller_than(v, kSmallHoleTargets * size))
      size = std::min(size, std::max(kFixedSegmentSizing * fixed_segment, opt.min_length));
    // A curved feature line needs its own resolution: a chord of a circle of radius r stays
    // within eps of the arc when it is shorter than sqrt(8 r eps - 4 eps^2).
    if (vclass[v] == kFeatureLine && n_ends == 2) {
      const Point& p = mesh.position(v);
      const Vec3 in = p - mesh.position(ends[0]), out = mesh.position(ends[1]) - p;
      const double turn = portable::atan2(glm::length(glm::cross(in, out)), glm::dot(in, out));
      const double span = 0.5 * (glm::length(in) + glm::length(out));
      // A sharper turn is a corner of the line, not a curve to resolve.
      if (turn > 0 && turn < kMaxCurveTurn && span > 0) {
        // A line curving tighter than the tolerance (r < eps) lies within eps of any chord up to
        // 2 eps long, the formula's value at r = eps: past it the formula falls again, and a coarser
        // tolerance would ask for shorter edges (see sizing_from_curvature).
        const double r = span / turn, e = opt.epsilon;
        const double chord2 = r > e ? 8 * r * e - 4 * e * e : 4 * e * e;
        size = std::min(size, std::max(std::sqrt(chord2), opt.min_length));
      }
    }
    sizing[v] = size;
  }
}

// Whether v lies on a border loop shorter than `limit` (a hole smaller than the target length).
// Walks at most kSmallHoleEdges edges.
bool Remesher::Impl::hole_smaller_than(Vertex v, double limit) const {
  Halfedge start;
  for (Halfedge h : mesh.halfedges(v))
    if (mesh.is_boundary(h)) start = h;
  if (!start.is_valid()) return false;
  double length = 0;
  Halfedge h = start;
  for (int i = 0; i < kSmallHoleEdges; ++i) {
    length += glm::length(mesh.position(mesh.to_vertex(h)) - mesh.position(mesh.from_vertex(h)));
    if (length >= limit) return false;
    h = mesh.next(h);
    if (h == start) return true;
  }
  return false;
}

// Raw discrete curvature is noisy on scanned meshes and the noise would show as needless size
// variation: one smoothing step with the free neighbours (kappa read from `kappa`, per slot).
static double smoothed_curvature(const SurfaceMesh& mesh, const VertexProperty<std::uint8_t>& vclass,
                                 const std::vector<double>& kappa, const std::vector<std::uint8_t>* known, Vertex v) {
  double sum = 0;
  int n = 0;
  for (Vertex w : mesh.vertices(v))
    if (vclass[w] == kFree && (!known || (*known)[w.idx])) {
      sum += kappa[w.idx];
      ++n;
    }
  return n ? 0.5 * kappa[v.idx] + 0.5 * sum / n : kappa[v.idx];
}

// The same field as build_reference() computes for the whole mesh (smoothed curvature,
// feature averaging, bounded gradation), restricted to the given vertices and measured on the
// current surface, so that a sculpting frame and a whole-mesh remesh agree on the sizes.
void Remesher::Impl::compute_sizing_from_current_surface(const std::vector<Vertex>& vertices) {
  if (!opt.adaptive) {
    for (Vertex v : vertices) sizing[v] = opt.target_length;
    return;
  }
  // kappa_known marks the given vertices only, and is cleared again below: the sculpting frames
  // call this on a few hundred vertices of a mesh that may have millions.
  mesh::resize_scratch(kappa, mesh.vertices_size());
  mesh::resize_scratch(kappa_known, mesh.vertices_size(), std::uint8_t(0));
  for (Vertex v : vertices) kappa_known[v.idx] = 1;
  if (clamp_decides_sizing()) {
    for (Vertex v : vertices)
      if (vclass[v] == kFree) sizing[v] = opt.min_length;
  } else {
    for (Vertex v : vertices) kappa[v.idx] = geometry::max_abs_curvature(mesh, v);
    for (Vertex v : vertices)
      if (vclass[v] == kFree)
        sizing[v] = sizing_from_curvature(smoothed_curvature(mesh, vclass, kappa, &kappa_known, v), opt.epsilon,
                                          opt.min_length, opt.max_length);
  }
  average_feature_sizing(vertices);
  // A region meets the untouched mesh at its held border. Where that mesh is finer than the
  // target (a brush coarsening a fine scan), the border's vertices keep their own mean edge
  // length and the gradation limit grades the region up from there: before, the region met the
  // fine mesh in a ring of slivers (bunny, target 2.8x its edges: 10-13 % of the brushed
  // triangles under 30 degrees, down to 7 degrees; now 0.6-0.8 %, 23 degrees). Part of the region
  // stays finer than the target (bunny: mean edge 0.5x the target instead of 0.8x).
  for (Vertex v : vertices) {
    if (scope[v] != kHeld) continue;
    double sum = 0;
    int n = 0;
    for (Halfedge h : mesh.halfedges(v)) {
      sum += glm::length(mesh.position(mesh.to_vertex(h)) - mesh.position(v));
      ++n;
    }
    if (sum > 0) sizing[v] = std::min(sizing[v], sum / n);
  }
  limit_sizing_gradation(mesh, vertices, sizing, kGradation, &kappa_known);
  for (Vertex v : vertices) kappa_known[v.idx] = 0;
  if (mirror_axis >= 0) symmetrize_sizing(vertices);
}

void Remesher::Impl::build_reference() {
  // Anchors name points of the reference this replaces.
  std::fill(anchor.vector().begin(), anchor.vector().end(), UINT32_MAX);
  std::vector<Vertex> all;
  all.reserve(mesh.n_vertices());
  for (Vertex v : mesh.vertices()) all.push_back(v);
  // The tree first: the sizing measures the thickness of thin parts on it.
  std::vector<Point> points(mesh.positions().begin(), mesh.positions().end());
  std::vector<std::array<std::uint32_t, 3>> triangles;
  triangles.reserve(mesh.n_faces());
  for (mesh::Face f : mesh.faces()) {
    Vertex c[3];
    mesh.face_vertices(f, c);
    triangles.push_back({c[0].idx, c[1].idx, c[2].idx});
  }
  tree.build(std::move(points), std::move(triangles));
  has_reference = !tree.empty();
  mark_line_kinks();
  mark_reference_tips();

  if (opt.adaptive) {
    if (clamp_decides_sizing()) {
      for (Vertex v : all)
        if (vclass[v] == kFree) sizing[v] = opt.min_length;
    } else {
      geometry::max_abs_curvature(mesh, kappa);
      for (Vertex v : all)
        if (vclass[v] == kFree)
          sizing[v] = sizing_from_curvature(smoothed_curvature(mesh, vclass, kappa, nullptr, v), opt.epsilon,
                                            opt.min_length, opt.max_length);
    }
    clamp_sizing_to_thickness(all);
    average_feature_sizing(all);
    clamp_sizing_to_strips();
    clamp_sizing_to_short_lines();
    limit_sizing_gradation(mesh, all, sizing, kGradation);
  } else {
    for (Vertex v : all) sizing[v] = opt.target_length;
  }

  ref_sizing.assign(sizing.vector().begin(), sizing.vector().end());
  estimate_vertex_budget();
  crease_samples.clear();
  crease_samples_due = true;
  build_reference_normals();
  ref_near_neck.assign(tree.points().size(), 0);
  necks.clear();
  // Incidence of the tree's triangles (it drops degenerate ones and reorders).
  const auto& tris = tree.triangles();
  ref_fan_offset.assign(tree.points().size() + 1, 0);
  for (const auto& t : tris)
    for (auto i : t) ++ref_fan_offset[i + 1];
  for (size_t i = 1; i < ref_fan_offset.size(); ++i) ref_fan_offset[i] += ref_fan_offset[i - 1];
  ref_fan.resize(ref_fan_offset.back());
  std::vector<std::uint32_t> fill(ref_fan_offset.begin(), ref_fan_offset.end() - 1);
  for (std::uint32_t ti = 0; ti < tris.size(); ++ti)
    for (auto i : tris[ti]) ref_fan[fill[i]++] = ti;
  build_reference_star_turns();

  // Neighbours across edges: the other triangle in both endpoints' fans.
  ref_adjacent.assign(tris.size(), {UINT32_MAX, UINT32_MAX, UINT32_MAX});
  for (std::uint32_t ti = 0; ti < tris.size(); ++ti)
    for (int i = 0; i < 3; ++i) {
      std::uint32_t a = tris[ti][i], b = tris[ti][(i + 1) % 3];
      for (std::uint32_t k = ref_fan_offset[a]; k < ref_fan_offset[a + 1]; ++k) {
        std::uint32_t other = ref_fan[k];
        if (other == ti) continue;
        const auto& t = tris[other];
        if (t[0] == b || t[1] == b || t[2] == b) {
          ref_adjacent[ti][i] = other;
          break;
        }
      }
    }

  ref_segments.clear();
  for (Edge e : mesh.edges())
    if (is_feature(e)) ref_segments.push_back({mesh.vertex(e, 0).idx, mesh.vertex(e, 1).idx});
  ref_segment_offset.assign(tree.points().size() + 1, 0);
  for (const auto& s : ref_segments)
    for (auto i : s) ++ref_segment_offset[i + 1];
  for (size_t i = 1; i < ref_segment_offset.size(); ++i) ref_segment_offset[i] += ref_segment_offset[i - 1];
  ref_segment_of_point.resize(ref_segment_offset.back());
  fill.assign(ref_segment_offset.begin(), ref_segment_offset.end() - 1);
  for (std::uint32_t si = 0; si < ref_segments.size(); ++si)
    for (auto i : ref_segments[si]) ref_segment_of_point[fill[i]++] = si;
  // Every line vertex lies on the segments at its own point: the natural first hint.
  for (Vertex v : mesh.vertices()) {
    const std::uint32_t first = ref_segment_offset[v.idx];
    segment_hint[v] = first < ref_segment_offset[v.idx + 1] ? ref_segment_of_point[first] : UINT32_MAX;
  }
  // Every vertex lies on the triangles of its own fan: the natural first hint.
  for (Vertex v : mesh.vertices()) {
    const std::uint32_t first = ref_fan_offset[v.idx];
    ref_hint[v] = first < ref_fan_offset[v.idx + 1] ? ref_fan[first] : UINT32_MAX;
  }
  reference_stale = false;
}

// Vertices move by a fraction of an edge per iteration, so their closest reference point is
// near the previous one: walk from the hint triangle over the triangles around its corners
// until no neighbour is closer (a handful of triangle tests instead of a tree descent).
// Without a hint, or when the walk does not settle, the AABB tree answers exactly.
// With `facing`, the answer is the nearest among the triangles facing that side
// (TriangleTree::closest_point_facing): the tree answers when the walk ends on a triangle facing
// the other way (a walk started on the other sheet of a thin part stops there, at a local
// minimum) or farther than `far`.
geometry::TriangleTree::ClosestHit Remesher::Impl::closest_on_reference(const Point& p, std::uint32_t hint,
                                                                        const Vec3* facing, double far) const {
  const auto& tris = tree.triangles();
  geometry::TriangleTree::ClosestHit walked;
  if (hint < tris.size()) walked = walk_reference(p, hint);
  if (!facing) return walked.triangle != UINT32_MAX ? walked : tree.closest_point(p);
  if (walked.triangle != UINT32_MAX && walked.distance2 <= far * far && tree.faces(walked.triangle, *facing))
    return walked;
  const geometry::TriangleTree::ClosestHit exact = tree.closest_point_facing(p, *facing, &walked);
  return exact.triangle != UINT32_MAX ? exact : walked.triangle != UINT32_MAX ? walked : tree.closest_point(p);
}

// The walk itself: from the hint triangle over neighbouring triangles while one is closer. Ends
// at a local minimum of the distance, or after 16 steps with the tree's exact answer.
geometry::TriangleTree::ClosestHit Remesher::Impl::walk_reference(const Point& p, std::uint32_t hint) const {
  const auto& tris = tree.triangles();
  const auto& pts = tree.points();
  geometry::TriangleTree::ClosestHit best;
  // Triangles already measured in this query: neighbouring fans overlap, and each walk step
  // revisits most of the previous one.
  constexpr int kSeenMax = 96;
  std::uint32_t seen[kSeenMax];
  int n_seen = 0;
  auto test = [&](std::uint32_t ti) {
    for (int i = 0; i < n_seen; ++i)
      if (seen[i] == ti) return false;
    if (n_seen < kSeenMax) seen[n_seen++] = ti;
    const auto& t = tris[ti];
    double bary[3];
    Point q = geometry::closest_point_on_triangle(p, pts[t[0]], pts[t[1]], pts[t[2]], bary);
    Vec3 d = q - p;
    double d2 = glm::dot(d, d);
    if (d2 < best.distance2) {
      best.distance2 = d2;
      best.point = q;
      best.triangle = ti;
      best.bary[0] = bary[0];
      best.bary[1] = bary[1];
      best.bary[2] = bary[2];
      return true;
    }
    return false;
  };
  best.distance2 = std::numeric_limits<double>::infinity();
  test(hint);
  for (int step = 0; step < 16; ++step) {
    const std::uint32_t centre = best.triangle;
    bool improved = false;
    for (std::uint32_t n : ref_adjacent[centre])
      if (n != UINT32_MAX) improved |= test(n);
    if (!improved) {
      // Closest to a corner: the triangles around it that share no edge with the centre.
      for (int i = 0; i < 3; ++i)
        if (best.bary[i] > 1.0 - 1e-9) {
          const std::uint32_t corner = tris[centre][i];
          for (std::uint32_t k = ref_fan_offset[corner]; k < ref_fan_offset[corner + 1]; ++k)
            improved |= test(ref_fan[k]);
        }
    }
    if (!improved) {
      // Ending on an edge with no triangle across it is a local minimum of the walk only: the
      // tree drops zero-area triangles, so a strip of them (degtri_sliding.off: collinear
      // triangles joining two flat parts) leaves a gap the walk cannot cross. Taken as the
      // answer, it projected the vertices beside the gap onto its line and made them collinear:
      // 13,261 zero-area triangles out of 18,444 at --uniform --length 0.5%. The tree answers
      // there (a true border costs the same, for vertices just beyond it).
      for (int i = 0; i < 3; ++i)
        if (ref_adjacent[centre][i] == UINT32_MAX && best.bary[(i + 2) % 3] <= 1e-9)
          return tree.closest_point(p, best);
      return best;
    }
  }
  return tree.closest_point(p, best);
}

double Remesher::Impl::reference_sizing_at(const Point& p, std::uint32_t* hint_triangle) const {
  geometry::TriangleTree::ClosestHit hit = closest_on_reference(p, *hint_triangle);
  *hint_triangle = hit.triangle;
  return sizing_of_hit(hit);
}

void Remesher::Impl::project(Vertex v) { project(v, vclass[v] == kFree ? fan_shape(v).normal : Vec3(0.0)); }

void Remesher::Impl::project(Vertex v, const Vec3& normal) {
  // A free vertex projects onto the reference triangles that face its own way: on a part thinner
  // than an edge the nearest reference point may lie on the opposite sheet (gen/thin_plate: a
  // vertex of the bottom, its walk started from a hint on the top, went to the top and took its
  // fan with it: 24k crossing pairs after the first projection).
  const bool oriented = vclass[v] == kFree && glm::dot(normal, normal) > 0;
  geometry::TriangleTree::ClosestHit hit =
      oriented ? closest_on_reference(mesh.position(v), ref_hint[v], &normal, kFarProjection * sizing[v])
               : closest_on_reference(mesh.position(v), ref_hint[v]);
  ref_hint[v] = hit.triangle;
  // Feature vertices go onto the nearest reference feature line instead: the nearest surface
  // point of a vertex beside a sharp edge lies on one of its faces, off the edge.
  if (vclass[v] != kFree) {
    project_onto_feature_line(v);
  } else {
    const Point p = mesh.position(v);
    const Vec3 d = hit.point - p;
    const double far = kFarProjection * sizing[v];
    if (glm::dot(d, d) <= far * far) {
      mesh.position(v) = hit.point;
    } else {
      // Relaxation moves a vertex by a fraction of an edge along the surface: its closest
      // reference point lies right below it. One that far away sits beside a fold, where the
      // surface turns back within less than an edge (dragon.off has fins 0.02% of the diagonal
      // thick, folded over): every point around such an edge is closest to the edge itself,
      // and snapping there lines vertices up on it, crumpling the fans between them. Only the
      // move along the vertex normal is taken (dragon: self-intersecting pairs, none of them
      // in the input, 19 -> 8; Hausdorff 0.54% -> 0.45%; the other shared meshes unchanged).
      const Vec3& n = normal;  // the fan's normal (zero when degenerate)
      const double nn = glm::dot(n, n);
      mesh.position(v) = nn > 0 ? p + n * (glm::dot(n, d) / nn) : hit.point;
    }
  }
  if (vclass[v] == kFree || !opt.adaptive)
    sizing[v] = sizing_of_hit(hit);
}

// Like the triangle walk: from the hint segment over the segments sharing an endpoint until
// none is closer; without a hint, every reference feature segment is tried once.
std::uint32_t Remesher::Impl::nearest_line_segment(const Point& p, std::uint32_t hint) const {
  const auto& pts = tree.points();
  std::uint32_t best = hint;
  double best_d2 = std::numeric_limits<double>::infinity();
  auto test = [&](std::uint32_t si) {
    const Point q = geometry::closest_point_on_segment(p, pts[ref_segments[si][0]], pts[ref_segments[si][1]]);
    const double d2 = glm::dot(q - p, q - p);
    if (!(d2 < best_d2)) return false;
    best_d2 = d2;
    best = si;
    return true;
  };
  if (best >= ref_segments.size()) {
    for (std::uint32_t si = 0; si < ref_segments.size(); ++si) test(si);
    return best;
  }
  test(best);
  for (int step = 0; step < 16; ++step) {
    const std::uint32_t centre = best;
    bool improved = false;
    for (auto end : ref_segments[centre])
      for (std::uint32_t k = ref_segment_offset[end]; k < ref_segment_offset[end + 1]; ++k)
        improved |= test(ref_segment_of_point[k]);
    if (!improved) break;
  }
  return best;
}

void Remesher::Impl::project_onto_feature_line(Vertex v) {
  if (ref_segments.empty()) return;
  const std::uint32_t s = nearest_line_segment(mesh.position(v), segment_hint[v]);
  segment_hint[v] = s;
  const auto& pts = tree.points();
  mesh.position(v) = geometry::closest_point_on_segment(mesh.position(v), pts[ref_segments[s][0]], pts[ref_segments[s][1]]);
}

}  // namespace adasculpt::remesh
