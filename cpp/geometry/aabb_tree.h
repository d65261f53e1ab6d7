#pragma once
// TriangleTree: a bounding volume hierarchy over triangles for exact closest-point and
// ray queries, e.g. projecting remeshed vertices back onto the reference surface and
// picking the surface under the mouse.
//
// Binned-SAH BVH in flat arrays, nodes in depth-first order (left child follows its parent), triangle
// corners copied into leaf order so a leaf is one contiguous read. Queries use a fixed
// stack on the call stack and never allocate, so they are safe to run from many threads
// on one const tree.
#include <array>
#include <limits>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>

#include "mesh/surface_mesh.h"
#include "mesh/types.h"

namespace adasculpt::geometry {

// Moller-Trumbore without back-face culling (the sign of det only tells the side): true when the
// ray origin + t * dir meets triangle (a, b, c) at t >= 0, with *t and the barycentrics u, v of
// b and c (the point is a + u (b - a) + v (c - a)). Shared by the trees' ray queries.
inline bool ray_triangle(const Point& origin, const Vec3& dir, const Point& a, const Point& b, const Point& c,
                         double* t, double* u, double* v) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 pv = glm::cross(dir, e2);
  const double det = glm::dot(e1, pv);
  if (det == 0.0) return false;
  const double inv_det = 1.0 / det;
  const Vec3 tv = origin - a;
  *u = glm::dot(tv, pv) * inv_det;
  if (*u < 0.0 || *u > 1.0) return false;
  const Vec3 qv = glm::cross(tv, e1);
  *v = glm::dot(dir, qv) * inv_det;
  if (*v < 0.0 || *u + *v > 1.0) return false;
  *t = glm::dot(e2, qv) * inv_det;
  return *t >= 0.0;
}

class TriangleTree {
 public:
  struct ClosestHit {
    Point point{0.0};
    std::uint32_t triangle = UINT32_MAX;  // index into triangles()
    double bary[3] = {0, 0, 0};
    double distance2 = 0;  // squared distance from the query
  };
  struct RayHit {
    bool hit = false;
    double t = 0;  // point = origin + t * dir
    std::uint32_t triangle = UINT32_MAX;
    Point point{0.0};
    double bary[3] = {0, 0, 0};
  };

  // Zero-area triangles are left out: they add nothing to the surface and would only
  // produce unstable barycentric coordinates.
  void build(std::vector<Point> points, std::vector<std::array<std::uint32_t, 3>> triangles);
  // Copies the live faces of the mesh; face_of() maps a tree triangle back to its Face.
  void build(const mesh::SurfaceMesh& mesh);

  bool empty() const { return tris_.empty(); }
  const std::vector<Point>& points() const { return points_; }
  // The kept triangles, in tree order (what ClosestHit::triangle and RayHit::triangle index).
  const std::vector<std::array<std::uint32_t, 3>>& triangles() const { return tris_; }
  // The input triangle (or mesh Face) a tree triangle came from.
  mesh::Face face_of(std::uint32_t tri) const { return mesh::Face(source_[tri]); }

  // Exact nearest point of the surface. Precondition: !empty().
  ClosestHit closest_point(const Point& q) const;
  // Warm start: the hint's triangle (typically the previous hit of a nearby query) gives
  // the initial bound, which prunes most of the tree at once.
  ClosestHit closest_point(const Point& q, const ClosestHit& hint) const;
  // Nearest point among the triangles whose normal (right-hand rule) points to the side of
  // `facing`: dot(normal, facing) > 0. A vertex of a thin part looks for its own sheet this way,
  // not the opposite side that may lie nearer (see remesh/reference.cpp). The hint as above; a
  // hint that does not face is ignored. triangle == UINT32_MAX when no triangle faces that way.
  ClosestHit closest_point_facing(const Point& q, const Vec3& facing, const ClosestHit* hint = nullptr) const;
  // Whether tree triangle `tri` faces the side of `facing` (as above).
  bool faces(std::uint32_t tri, const Vec3& facing) const;
  // Nearest intersection with 0 <= t < t_max of the ray origin + t*dir, front or back side. A
  // finite t_max prunes every box beyond it (a short probe costs a few nodes, not a traversal).
  RayHit intersect_ray(const Point& origin, const Vec3& dir,
                       double t_max = std::numeric_limits<double>::infinity()) const;

 private:
  struct Node {
    Point lo, hi;
    std::uint32_t first;  // leaf: first triangle; inner: index of the right child
    std::uint32_t count;  // > 0 for a leaf
  };
  static constexpr std::uint32_t kLeafSize = 4;
  static constexpr int kMaxDepth = 64;

  // Per triangle (in tris_ order): its centroid and bounding box, computed once for the build.
  struct BuildInput {
    std::vector<Point> centroids, lo, hi;
  };
  std::uint32_t split(std::vector<std::uint32_t>& order, const BuildInput& in, std::uint32_t first,
                      std::uint32_t count, int depth) const;
  std::uint32_t build_node(std::vector<std::uint32_t>& order, const BuildInput& in, std::uint32_t first,
                          std::uint32_t count, int depth);
  template <class Accept>
  void search(const Point& q, ClosestHit& best, Accept&& accept) const;
  void test_triangle(const Point& q, std::uint32_t tri, ClosestHit& best) const;

  std::vector<Point> points_;
  std::vector<std::array<std::uint32_t, 3>> tris_;
  std::vector<std::array<Point, 3>> corners_;  // per tree triangle
  std::vector<std::uint32_t> source_;          // per tree triangle: input index / Face index
  std::vector<Node> nodes_;
};

}  // namespace adasculpt::geometry
