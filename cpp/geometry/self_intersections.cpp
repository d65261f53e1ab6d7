#include "geometry/self_intersections.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/geometric.hpp>

#include "geometry/exact_predicates.h"

namespace adasculpt::geometry {

namespace {

// ---- exact tests in a plane ------------------------------------------------------------
// Coplanar configurations are decided in 2D: dropping one coordinate is an exact affine
// bijection of the plane onto a coordinate plane as long as the plane is not perpendicular
// to it, so exact 2D orientations of the projected points are the exact 3D answers.

struct Projection {
  int i = 0, j = 1;  // the kept coordinates
  int orient(const Point& a, const Point& b, const Point& c) const {
    return orient2d(a[i], a[j], b[i], b[j], c[i], c[j]);
  }
};

// A projection in which the non-degenerate triangle t keeps a non-zero area. The largest
// component of the rounded normal nearly always works; the exact check makes it certain.
Projection projection_for(const Point t[3]) {
  const Vec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3, [&](int a, int b) { return std::fabs(n[a]) > std::fabs(n[b]); });
  for (int dropped : order) {
    Projection p{dropped == 0 ? 1 : 0, dropped == 2 ? 1 : 2};
    if (p.orient(t[0], t[1], t[2]) != 0) return p;
  }
  return Projection{};  // collinear triangle: excluded by every caller
}

// p on the closed segment ab, given that the three are collinear.
bool within_box(const Projection& pr, const Point& p, const Point& a, const Point& b) {
  for (int k : {pr.i, pr.j})
    if (p[k] < std::min(a[k], b[k]) || p[k] > std::max(a[k], b[k])) return false;
  return true;
}

bool segments_intersect_2d(const Projection& pr, const Point& a, const Point& b, const Point& c, const Point& d) {
  const int o1 = pr.orient(a, b, c), o2 = pr.orient(a, b, d);
  const int o3 = pr.orient(c, d, a), o4 = pr.orient(c, d, b);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && within_box(pr, c, a, b)) || (o2 == 0 && within_box(pr, d, a, b)) ||
         (o3 == 0 && within_box(pr, a, c, d)) || (o4 == 0 && within_box(pr, b, c, d));
}

bool point_in_triangle_2d(const Projection& pr, const Point& p, const Point t[3]) {
  const int o1 = pr.orient(t[0], t[1], p), o2 = pr.orient(t[1], t[2], p), o3 = pr.orient(t[2], t[0], p);
  return (o1 >= 0 && o2 >= 0 && o3 >= 0) || (o1 <= 0 && o2 <= 0 && o3 <= 0);
}

bool segment_meets_edges_2d(const Projection& pr, const Point& a, const Point& b, const Point t[3]) {
  for (int k = 0; k < 3; ++k)
    if (segments_intersect_2d(pr, a, b, t[k], t[(k + 1) % 3])) return true;
  return false;
}

// ---- exact tests in space --------------------------------------------------------------

// Segment ab against triangle t, with sa, sb the sides of a and b relative to t's plane.
bool segment_hits_triangle(const Point& a, const Point& b, int sa, int sb, const Point t[3]) {
  if (sa * sb > 0) return false;
  if (sa == 0 && sb == 0) {
    const Projection pr = projection_for(t);
    return point_in_triangle_2d(pr, a, t) || point_in_triangle_2d(pr, b, t) || segment_meets_edges_2d(pr, a, b, t);
  }
  // The segment meets the plane in one point; the line through it pierces the closed
  // triangle iff every edge of t passes the line ab on the same side (or touches it).
  const int o1 = orient3d(a, b, t[0], t[1]), o2 = orient3d(a, b, t[1], t[2]), o3 = orient3d(a, b, t[2], t[0]);
  return (o1 >= 0 && o2 >= 0 && o3 >= 0) || (o1 <= 0 && o2 <= 0 && o3 <= 0);
}

bool all_same_strict_side(const int s[3]) {
  return (s[0] > 0 && s[1] > 0 && s[2] > 0) || (s[0] < 0 && s[1] < 0 && s[2] < 0);
}

// ---- broad phase: a bounding volume hierarchy over face boxes ---------------------------

struct Box {
  Point lo, hi;
  bool overlaps(const Box& o) const {  // closed boxes: touching faces have touching boxes
    return lo.x <= o.hi.x && o.lo.x <= hi.x && lo.y <= o.hi.y && o.lo.y <= hi.y && lo.z <= o.hi.z &&
           o.lo.z <= hi.z;
  }
};

class BoxTree {
 public:
  explicit BoxTree(const std::vector<Box>& boxes) : boxes_(boxes), order_(boxes.size()) {
    std::iota(order_.begin(), order_.end(), 0u);
    if (!boxes.empty()) build(0, static_cast<std::uint32_t>(boxes.size()));
  }

  // Calls visit(a, b) once for every unordered pair of distinct boxes that overlap;
  // visit returns false to stop the search.
  template <class Visit>
  void overlapping_pairs(Visit&& visit) const {
    if (nodes_.empty()) return;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> stack{{0, 0}};
    while (!stack.empty()) {
      const auto [a, b] = stack.back();
      stack.pop_back();
      const Node &na = nodes_[a], &nb = nodes_[b];
      if (a == b) {
        if (na.count > 0) {
          for (std::uint32_t i = na.first; i < na.first + na.count; ++i)
            for (std::uint32_t j = i + 1; j < na.first + na.count; ++j)
              if (!test(i, j, visit)) return;
        } else {
          stack.push_back({a + 1, a + 1});
          stack.push_back({na.first, na.first});
          stack.push_back({a + 1, na.first});
        }
        continue;
      }
      if (!na.box.overlaps(nb.box)) continue;
      if (na.count > 0 && nb.count > 0) {
        for (std::uint32_t i = na.first; i < na.first + na.count; ++i)
          for (std::uint32_t j = nb.first; j < nb.first + nb.count; ++j)
            if (!test(i, j, visit)) return;
      } else if (na.count > 0 || (nb.count == 0 && nb.size > na.size)) {
        stack.push_back({a, b + 1});
        stack.push_back({a, nb.first});
      } else {
        stack.push_back({a + 1, b});
        stack.push_back({na.first, b});
      }
    }
  }

 private:
  struct Node {
    Box box;
    std::uint32_t first;  // leaf: first slot in order_; inner: index of the right child
    std::uint32_t count;  // > 0 for a leaf (the left child of an inner node follows it)
    std::uint32_t size;   // boxes below
  };
  static constexpr std::uint32_t kLeafSize = 4;

  template <class Visit>
  bool test(std::uint32_t slot_i, std::uint32_t slot_j, Visit& visit) const {
    const std::uint32_t i = order_[slot_i], j = order_[slot_j];
    if (!boxes_[i].overlaps(boxes_[j])) return true;
    return visit(i, j);
  }

  // Median split along the longest axis of the centres; depth is logarithmic.
  std::uint32_t build(std::uint32_t first, std::uint32_t count) {
    const std::uint32_t index = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back({});
    Box box = boxes_[order_[first]];
    for (std::uint32_t k = first + 1; k < first + count; ++k) {
      box.lo = glm::min(box.lo, boxes_[order_[k]].lo);
      box.hi = glm::max(box.hi, boxes_[order_[k]].hi);
    }
    if (count <= kLeafSize) {
      nodes_[index] = {box, first, count, count};
      return index;
    }
    const Vec3 extent = box.hi - box.lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const std::uint32_t half = count / 2;
    auto centre = [&](std::uint32_t f) { return boxes_[f].lo[axis] + boxes_[f].hi[axis]; };
    std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                     [&](std::uint32_t a, std::uint32_t b) { return centre(a) < centre(b); });
    build(first, half);
    const std::uint32_t right = build(first + half, count - half);
    nodes_[index] = {box, right, 0, count};
    return index;
  }

  const std::vector<Box>& boxes_;
  std::vector<std::uint32_t> order_;
  std::vector<Node> nodes_;
};

}  // namespace

bool collinear(const Point& a, const Point& b, const Point& c) {
  return orient2d(a.x, a.y, b.x, b.y, c.x, c.y) == 0 && orient2d(a.y, a.z, b.y, b.z, c.y, c.z) == 0 &&
         orient2d(a.z, a.x, b.z, b.x, c.z, c.x) == 0;
}

bool segment_intersects_triangle(const Point& a, const Point& b, const Point t[3]) {
  return segment_hits_triangle(a, b, orient3d(t[0], t[1], t[2], a), orient3d(t[0], t[1], t[2], b), t);
}

bool triangles_intersect(const Point p[3], const Point q[3]) {
  int q_side[3], p_side[3];
  for (int k = 0; k < 3; ++k) q_side[k] = orient3d(p[0], p[1], p[2], q[k]);
  if (all_same_strict_side(q_side)) return false;
  for (int k = 0; k < 3; ++k) p_side[k] = orient3d(q[0], q[1], q[2], p[k]);
  if (all_same_strict_side(p_side)) return false;
  if (q_side[0] == 0 && q_side[1] == 0 && q_side[2] == 0) {
    const Projection pr = projection_for(p);
    for (int k = 0; k < 3; ++k)
      if (segment_meets_edges_2d(pr, p[k], p[(k + 1) % 3], q)) return true;
    return point_in_triangle_2d(pr, p[0], q) || point_in_triangle_2d(pr, q[0], p);
  }
  // Two closed triangles meet iff an edge of one meets the other: an extreme point of
  // their (convex) intersection lies on the boundary of one of them.
  for (int k = 0; k < 3; ++k) {
    const int l = (k + 1) % 3;
    if (segment_hits_triangle(p[k], p[l], p_side[k], p_side[l], q)) return true;
    if (segment_hits_triangle(q[k], q[l], q_side[k], q_side[l], p)) return true;
  }
  return false;
}

bool faces_intersect(const std::vector<Point>& points, const std::array<std::uint32_t, 3>& t,
                     const std::array<std::uint32_t, 3>& u) {
  const Point tp[3] = {points[t[0]], points[t[1]], points[t[2]]};
  const Point up[3] = {points[u[0]], points[u[1]], points[u[2]]};
  return faces_intersect(tp, t, up, u);
}

bool faces_intersect(const Point tp[3], const std::array<std::uint32_t, 3>& t, const Point up[3],
                     const std::array<std::uint32_t, 3>& u) {
  int shared = 0, t_at = -1, u_at = -1;  // positions of a shared vertex in t and u
  int t_shared_mask = 0, u_shared_mask = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (t[i] == u[j]) {
        ++shared, t_at = i, u_at = j;
        t_shared_mask |= 1 << i, u_shared_mask |= 1 << j;
      }
  if (shared == 0) return triangles_intersect(tp, up);
  if (shared == 3) return true;  // the same triangle twice
  if (shared == 2) {
    // Across a common edge pq the two faces can only meet elsewhere by folding onto each
    // other: coplanar, with the third corners r and s on the same side of pq.
    const int r = t_shared_mask == 3 ? 2 : (t_shared_mask == 5 ? 1 : 0);
    const int s = u_shared_mask == 3 ? 2 : (u_shared_mask == 5 ? 1 : 0);
    const Point &p = tp[(r + 1) % 3], &q = tp[(r + 2) % 3];
    if (orient3d(p, q, tp[r], up[s]) != 0) return false;
    const Projection pr = projection_for(tp);
    return pr.orient(p, q, tp[r]) * pr.orient(p, q, up[s]) > 0;
  }
  // One common corner v: the faces meet elsewhere iff the edge opposite v in one of them
  // meets the other face.
  return segment_intersects_triangle(tp[(t_at + 1) % 3], tp[(t_at + 2) % 3], up) ||
         segment_intersects_triangle(up[(u_at + 1) % 3], up[(u_at + 2) % 3], tp);
}

SelfIntersectionReport self_intersections(const std::vector<Point>& points,
                                          const std::vector<std::array<std::uint32_t, 3>>& triangles,
                                          size_t max_pairs) {
  SelfIntersectionReport report;
  std::vector<std::uint32_t> kept;  // non-degenerate triangles
  std::vector<Box> boxes;
  kept.reserve(triangles.size());
  boxes.reserve(triangles.size());
  for (std::uint32_t f = 0; f < triangles.size(); ++f) {
    const Point &a = points[triangles[f][0]], &b = points[triangles[f][1]], &c = points[triangles[f][2]];
    if (collinear(a, b, c)) {
      ++report.degenerate_faces;
      continue;
    }
    kept.push_back(f);
    boxes.push_back({glm::min(a, glm::min(b, c)), glm::max(a, glm::max(b, c))});
  }
  if (max_pairs == 0) {
    report.capped = true;
    return report;
  }
  BoxTree tree(boxes);
  tree.overlapping_pairs([&](std::uint32_t i, std::uint32_t j) {
    const std::uint32_t f = kept[i], g = kept[j];
    if (!faces_intersect(points, triangles[f], triangles[g])) return true;
    report.pairs.emplace_back(std::min(f, g), std::max(f, g));
    if (report.pairs.size() < max_pairs) return true;
    report.capped = true;
    return false;
  });
  std::sort(report.pairs.begin(), report.pairs.end());
  return report;
}

SelfIntersectionReport self_intersections(const mesh::SurfaceMesh& mesh, size_t max_pairs) {
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::uint32_t> face_of;
  triangles.reserve(mesh.n_faces());
  face_of.reserve(mesh.n_faces());
  for (mesh::Face f : mesh.faces()) {
    mesh::Vertex v[3];
    mesh.face_vertices(f, v);
    triangles.push_back({v[0].idx, v[1].idx, v[2].idx});
    face_of.push_back(f.idx);
  }
  SelfIntersectionReport report = self_intersections(mesh.positions(), triangles, max_pairs);
  for (auto& [a, b] : report.pairs) a = face_of[a], b = face_of[b];
  std::sort(report.pairs.begin(), report.pairs.end());
  return report;
}

}  // namespace adasculpt::geometry
