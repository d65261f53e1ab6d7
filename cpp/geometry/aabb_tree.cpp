#include "geometry/aabb_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "geometry/triangle.h"

namespace adasculpt::geometry {

namespace {

double box_distance2(const Point& q, const Point& lo, const Point& hi) {
  Vec3 d = glm::max(glm::max(lo - q, q - hi), Vec3(0.0));
  return glm::dot(d, d);
}

}  // namespace

void TriangleTree::build(std::vector<Point> points, std::vector<std::array<std::uint32_t, 3>> triangles) {
  points_ = std::move(points);
  tris_.clear();
  source_.clear();
  for (std::uint32_t i = 0; i < triangles.size(); ++i) {
    const auto& t = triangles[i];
    if (t[0] >= points_.size() || t[1] >= points_.size() || t[2] >= points_.size())
      throw std::out_of_range("TriangleTree::build: triangle " + std::to_string(i) + " refers to a missing point");
    const Point &a = points_[t[0]], &b = points_[t[1]], &c = points_[t[2]];
    if (glm::length(glm::cross(b - a, c - a)) == 0.0) continue;
    tris_.push_back(t);
    source_.push_back(i);
  }
  // Each triangle's box once: the build reads them at every level (reading the corners there
  // instead was 7.7 % of a remesh of bunny.off at the defaults). Boxes and their unions are exact,
  // so the tree is the same.
  BuildInput in;
  in.centroids.resize(tris_.size());
  in.lo.resize(tris_.size());
  in.hi.resize(tris_.size());
  for (size_t i = 0; i < tris_.size(); ++i) {
    const Point &a = points_[tris_[i][0]], &b = points_[tris_[i][1]], &c = points_[tris_[i][2]];
    in.centroids[i] = (a + b + c) / 3.0;
    in.lo[i] = glm::min(glm::min(a, b), c);
    in.hi[i] = glm::max(glm::max(a, b), c);
  }
  std::vector<std::uint32_t> order(tris_.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  nodes_.clear();
  if (!order.empty()) {
    nodes_.reserve(2 * order.size() / kLeafSize + 1);
    build_node(order, in, 0, static_cast<std::uint32_t>(order.size()), 0);
  }

  // Store triangles in leaf order so that a leaf reads one contiguous block.
  std::vector<std::array<std::uint32_t, 3>> tris(order.size());
  std::vector<std::uint32_t> source(order.size());
  corners_.resize(order.size());
  for (size_t i = 0; i < order.size(); ++i) {
    tris[i] = tris_[order[i]];
    source[i] = source_[order[i]];
    corners_[i] = {points_[tris[i][0]], points_[tris[i][1]], points_[tris[i][2]]};
  }
  tris_ = std::move(tris);
  source_ = std::move(source);
}

void TriangleTree::build(const mesh::SurfaceMesh& mesh) {
  // Keep vertex slots as they are (deleted ones included) so no remapping is needed;
  // then translate tree indices (positions in this face list) back to Face indices.
  std::vector<std::array<std::uint32_t, 3>> tris;
  std::vector<std::uint32_t> faces;
  tris.reserve(mesh.n_faces());
  faces.reserve(mesh.n_faces());
  for (mesh::Face f : mesh.faces()) {
    mesh::Vertex v[3];
    mesh.face_vertices(f, v);
    tris.push_back({v[0].idx, v[1].idx, v[2].idx});
    faces.push_back(f.idx);
  }
  build(mesh.positions(), std::move(tris));
  for (auto& s : source_) s = faces[s];
}

// Splits [first, first+count) of order in two and returns the size of the left part.
// Binned surface-area heuristic on the longest centroid axis: fewer overlapping boxes than
// a median split, so fewer nodes visited per query. Falls back to the median when the
// heuristic cannot separate the centroids.
std::uint32_t TriangleTree::split(std::vector<std::uint32_t>& order, const BuildInput& in, std::uint32_t first,
                                  std::uint32_t count, int depth) const {
  const std::vector<Point>& centroids = in.centroids;
  Point clo(std::numeric_limits<double>::infinity()), chi(-std::numeric_limits<double>::infinity());
  for (std::uint32_t i = first; i < first + count; ++i) {
    clo = glm::min(clo, centroids[order[i]]);
    chi = glm::max(chi, centroids[order[i]]);
  }
  const Vec3 extent = chi - clo;
  const int axis = extent.x >= extent.y ? (extent.x >= extent.z ? 0 : 2) : (extent.y >= extent.z ? 1 : 2);
  auto begin = order.begin() + first, end = begin + count;
  const std::uint32_t half = count / 2;
  auto median = [&] {
    // Ties broken by index: the split must not depend on the standard library's algorithm,
    // or the native and WebAssembly builds (libstdc++ vs libc++) would build different trees.
    std::nth_element(begin, begin + half, end, [&](std::uint32_t a, std::uint32_t b) {
      return centroids[a][axis] < centroids[b][axis] || (centroids[a][axis] == centroids[b][axis] && a < b);
    });
    return half;
  };
  // Deep in the tree only the median keeps the depth (and so the query stack) bounded.
  if (!(extent[axis] > 0) || depth > kMaxDepth / 2) return median();

  constexpr int kBins = 16;
  struct Bin {
    Point lo{std::numeric_limits<double>::infinity()}, hi{-std::numeric_limits<double>::infinity()};
    std::uint32_t n = 0;
  };
  Bin bins[kBins];
  const double scale = kBins / extent[axis];
  auto bin_of = [&](std::uint32_t t) {
    return std::min(kBins - 1, static_cast<int>((centroids[t][axis] - clo[axis]) * scale));
  };
  for (auto it = begin; it != end; ++it) {
    Bin& b = bins[bin_of(*it)];
    ++b.n;
    b.lo = glm::min(b.lo, in.lo[*it]);
    b.hi = glm::max(b.hi, in.hi[*it]);
  }
  auto half_area = [](const Point& lo, const Point& hi) {
    const Vec3 d = hi - lo;
    return d.x * d.y + d.y * d.z + d.z * d.x;
  };
  // Sweep from the right to get the cost of every right part, then from the left.
  double right_cost[kBins];
  Point lo = bins[kBins - 1].lo, hi = bins[kBins - 1].hi;
  std::uint32_t n = 0;
  for (int i = kBins - 1; i > 0; --i) {
    lo = glm::min(lo, bins[i].lo);
    hi = glm::max(hi, bins[i].hi);
    n += bins[i].n;
    right_cost[i] = n ? n * half_area(lo, hi) : 0.0;
  }
  double best_cost = std::numeric_limits<double>::infinity();
  int best_bin = -1;
  lo = bins[0].lo, hi = bins[0].hi, n = 0;
  for (int i = 0; i < kBins - 1; ++i) {
    lo = glm::min(lo, bins[i].lo);
    hi = glm::max(hi, bins[i].hi);
    n += bins[i].n;
    if (n == 0 || n == count) continue;
    const double cost = n * half_area(lo, hi) + right_cost[i + 1];
    if (cost < best_cost) best_cost = cost, best_bin = i;
  }
  if (best_bin < 0) return median();
  // Stable, for the same reason as the tie-break above: identical trees on every platform.
  auto mid = std::stable_partition(begin, end, [&](std::uint32_t t) { return bin_of(t) <= best_bin; });
  return static_cast<std::uint32_t>(mid - begin);
}

std::uint32_t TriangleTree::build_node(std::vector<std::uint32_t>& order, const BuildInput& in, std::uint32_t first,
                                       std::uint32_t count, int depth) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.push_back(Node{});
  Point lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (std::uint32_t i = first; i < first + count; ++i) {
    lo = glm::min(lo, in.lo[order[i]]);
    hi = glm::max(hi, in.hi[order[i]]);
  }
  nodes_[index].lo = lo;
  nodes_[index].hi = hi;
  if (count <= kLeafSize) {
    // A leaf's triangles in input order, whatever order the partitioning left them in.
    std::sort(order.begin() + first, order.begin() + first + count);
    nodes_[index].first = first;
    nodes_[index].count = count;
    return index;
  }
  const std::uint32_t left = split(order, in, first, count, depth);
  build_node(order, in, first, left, depth + 1);  // lands at index + 1
  const std::uint32_t right = build_node(order, in, first + left, count - left, depth + 1);
  nodes_[index].first = right;
  nodes_[index].count = 0;
  return index;
}

void TriangleTree::test_triangle(const Point& q, std::uint32_t tri, ClosestHit& best) const {
  const auto& c = corners_[tri];
  double bary[3];
  Point p = closest_point_on_triangle(q, c[0], c[1], c[2], bary);
  Vec3 d = p - q;
  double d2 = glm::dot(d, d);
  if (d2 < best.distance2) {
    best.distance2 = d2;
    best.point = p;
    best.triangle = tri;
    best.bary[0] = bary[0], best.bary[1] = bary[1], best.bary[2] = bary[2];
  }
}

// Branch and bound: visit the nearer child first, skip any box farther than the best so far.
// Only triangles with accept(tri) take part.
template <class Accept>
void TriangleTree::search(const Point& q, ClosestHit& best, Accept&& accept) const {
  struct Entry {
    std::uint32_t node;
    double d2;
  };
  Entry stack[2 * kMaxDepth];  // holds at most depth + 1 entries
  int top = 0;
  stack[top++] = {0, box_distance2(q, nodes_[0].lo, nodes_[0].hi)};
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.d2 >= best.distance2) continue;
    const Node& n = nodes_[e.node];
    if (n.count > 0) {
      for (std::uint32_t i = n.first; i < n.first + n.count; ++i)
        if (accept(i)) test_triangle(q, i, best);
      continue;
    }
    std::uint32_t near = e.node + 1, far = n.first;
    double dn = box_distance2(q, nodes_[near].lo, nodes_[near].hi);
    double df = box_distance2(q, nodes_[far].lo, nodes_[far].hi);
    if (df < dn) std::swap(near, far), std::swap(dn, df);
    if (df < best.distance2) stack[top++] = {far, df};
    if (dn < best.distance2) stack[top++] = {near, dn};
  }
}

TriangleTree::ClosestHit TriangleTree::closest_point(const Point& q) const {
  ClosestHit best;
  best.distance2 = std::numeric_limits<double>::infinity();
  if (!nodes_.empty()) search(q, best, [](std::uint32_t) { return true; });
  return best;
}

TriangleTree::ClosestHit TriangleTree::closest_point(const Point& q, const ClosestHit& hint) const {
  ClosestHit best;
  best.distance2 = std::numeric_limits<double>::infinity();
  // The hint's own distance belongs to another query point; re-measure from q so the bound
  // is a true upper bound (exact answer, only faster).
  if (hint.triangle < corners_.size()) test_triangle(q, hint.triangle, best);
  if (!nodes_.empty()) search(q, best, [](std::uint32_t) { return true; });
  return best;
}

bool TriangleTree::faces(std::uint32_t tri, const Vec3& facing) const {
  const auto& c = corners_[tri];
  return glm::dot(glm::cross(c[1] - c[0], c[2] - c[0]), facing) > 0;
}

TriangleTree::ClosestHit TriangleTree::closest_point_facing(const Point& q, const Vec3& facing,
                                                            const ClosestHit* hint) const {
  ClosestHit best;
  best.distance2 = std::numeric_limits<double>::infinity();
  auto accept = [&](std::uint32_t tri) { return faces(tri, facing); };
  if (hint && hint->triangle < corners_.size() && accept(hint->triangle)) test_triangle(q, hint->triangle, best);
  if (!nodes_.empty()) search(q, best, accept);
  return best;
}

TriangleTree::RayHit TriangleTree::intersect_ray(const Point& origin, const Vec3& dir, double t_max) const {
  RayHit best;
  if (nodes_.empty()) return best;
  constexpr double kMiss = std::numeric_limits<double>::infinity();
  double t_best = t_max;
  // Slab test; an axis the ray is parallel to only checks that the origin is inside the slab
  // (avoids 0 * inf = NaN).
  Vec3 inv;
  bool parallel[3];
  for (int k = 0; k < 3; ++k) {
    parallel[k] = dir[k] == 0.0;
    inv[k] = parallel[k] ? 0.0 : 1.0 / dir[k];
  }
  auto box_entry = [&](const Node& n) {
    double t0 = 0.0, t1 = t_best;
    for (int k = 0; k < 3; ++k) {
      if (parallel[k]) {
        if (origin[k] < n.lo[k] || origin[k] > n.hi[k]) return std::numeric_limits<double>::infinity();
        continue;
      }
      double a = (n.lo[k] - origin[k]) * inv[k], b = (n.hi[k] - origin[k]) * inv[k];
      if (a > b) std::swap(a, b);
      t0 = std::max(t0, a);
      t1 = std::min(t1, b);
    }
    return t0 <= t1 ? t0 : std::numeric_limits<double>::infinity();
  };
  struct Entry {
    std::uint32_t node;
    double t;
  };
  Entry stack[2 * kMaxDepth];  // holds at most depth + 1 entries
  int top = 0;
  double t_root = box_entry(nodes_[0]);
  if (t_root == kMiss) return best;
  stack[top++] = {0, t_root};
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.t > t_best) continue;
    const Node& n = nodes_[e.node];
    if (n.count == 0) {
      std::uint32_t near = e.node + 1, far = n.first;
      double tn = box_entry(nodes_[near]), tf = box_entry(nodes_[far]);
      if (tf < tn) std::swap(near, far), std::swap(tn, tf);
      // A missed box reports +inf, which must not pass "<= t_best" while t_best is still inf.
      if (tf < kMiss && tf <= t_best) stack[top++] = {far, tf};
      if (tn < kMiss && tn <= t_best) stack[top++] = {near, tn};
      continue;
    }
    for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
      const auto& c = corners_[i];
      double t, u, v;
      if (!ray_triangle(origin, dir, c[0], c[1], c[2], &t, &u, &v) || t >= t_best) continue;
      t_best = t;
      best.hit = true;
      best.t = t;
      best.triangle = i;
      best.bary[0] = 1.0 - u - v, best.bary[1] = u, best.bary[2] = v;
      best.point = c[0] + u * (c[1] - c[0]) + v * (c[2] - c[0]);
    }
  }
  return best;
}

}  // namespace adasculpt::geometry
