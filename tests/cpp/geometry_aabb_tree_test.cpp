// TriangleTree against brute force: closest points and ray hits on random queries.
#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <random>

#include "geometry/aabb_tree.h"
#include "geometry/triangle.h"
#include "geometry_test_util.h"
#include "io/mesh_io.h"
#include "mesh/primitives.h"

using namespace adasculpt;
using namespace adasculpt::geometry;

namespace {

double brute_distance2(const TriangleTree& tree, const Point& q) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : tree.triangles()) {
    double bary[3];
    Point p = closest_point_on_triangle(q, tree.points()[t[0]], tree.points()[t[1]], tree.points()[t[2]], bary);
    best = std::min(best, glm::dot(p - q, p - q));
  }
  return best;
}

// Nearest t over all triangles by Moller-Trumbore (no tree).
double brute_ray(const TriangleTree& tree, const Point& o, const Vec3& d) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : tree.triangles()) {
    const Point &a = tree.points()[t[0]], &b = tree.points()[t[1]], &c = tree.points()[t[2]];
    Vec3 e1 = b - a, e2 = c - a, pv = glm::cross(d, e2);
    double det = glm::dot(e1, pv);
    if (det == 0) continue;
    Vec3 tv = o - a, qv = glm::cross(tv, e1);
    double u = glm::dot(tv, pv) / det, v = glm::dot(d, qv) / det, s = glm::dot(e2, qv) / det;
    if (u >= 0 && v >= 0 && u + v <= 1 && s >= 0) best = std::min(best, s);
  }
  return best;
}

void check_against_brute_force(const TriangleTree& tree, double scale, const Point& centre) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  TriangleTree::ClosestHit previous;
  int hits = 0;
  for (int i = 0; i < 1000; ++i) {
    Point q = centre + scale * Point(u(rng), u(rng), u(rng));
    auto hit = tree.closest_point(q);
    ASSERT_NEAR(hit.distance2, brute_distance2(tree, q), 1e-12 * scale * scale);
    const auto& t = tree.triangles()[hit.triangle];
    Point from_bary = hit.bary[0] * tree.points()[t[0]] + hit.bary[1] * tree.points()[t[1]] +
                      hit.bary[2] * tree.points()[t[2]];
    ASSERT_NEAR(glm::length(from_bary - hit.point), 0.0, 1e-12 * scale);
    if (i > 0) {  // warm start from the previous (unrelated) hit is still exact
      auto warm = tree.closest_point(q, previous);
      ASSERT_NEAR(warm.distance2, hit.distance2, 1e-15 * scale * scale);
    }
    previous = hit;

    Vec3 dir(u(rng), u(rng), u(rng));
    auto ray = tree.intersect_ray(q, dir);
    double t_ref = brute_ray(tree, q, dir);
    ASSERT_EQ(ray.hit, t_ref < std::numeric_limits<double>::infinity());
    if (ray.hit) {
      ++hits;
      ASSERT_NEAR(ray.t, t_ref, 1e-9 * (1 + t_ref));
      ASSERT_NEAR(glm::length(ray.point - (q + ray.t * dir)), 0.0, 1e-9 * scale);
    }
  }
  EXPECT_GT(hits, 50);
}

}  // namespace

TEST(GeometryAabbTree, IcosphereAgainstBruteForce) {
  TriangleTree tree;
  tree.build(mesh::make_icosphere(3, 2.0));
  ASSERT_FALSE(tree.empty());
  EXPECT_EQ(tree.triangles().size(), 1280u);
  check_against_brute_force(tree, 2.0, Point(0.0));
}

TEST(GeometryAabbTree, SharedMeshAgainstBruteForce) {
  const std::string path = test::shared_mesh("fandisk.off");
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not found";
  io::PolygonSoup soup = io::read_soup(path);
  std::vector<Point> pts;
  for (const auto& p : soup.points) pts.emplace_back(p[0], p[1], p[2]);
  Point lo = pts[0], hi = pts[0];
  for (const Point& p : pts) lo = glm::min(lo, p), hi = glm::max(hi, p);
  TriangleTree tree;
  tree.build(pts, soup.triangles);
  check_against_brute_force(tree, 0.5 * glm::length(hi - lo), 0.5 * (lo + hi));
}

TEST(GeometryAabbTree, SkipsZeroAreaTrianglesAndMapsFaces) {
  std::vector<Point> pts = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}};
  TriangleTree tree;
  tree.build(pts, {{0, 1, 3}, {0, 1, 2}});  // the first is collinear
  ASSERT_EQ(tree.triangles().size(), 1u);
  EXPECT_EQ(tree.face_of(0).idx, 1u);
  auto hit = tree.closest_point({0.2, 0.2, 1});
  EXPECT_NEAR(hit.distance2, 1.0, 1e-15);
  auto ray = tree.intersect_ray({0.2, 0.2, -1}, {0, 0, 1});  // from the back side
  EXPECT_TRUE(ray.hit);
  EXPECT_NEAR(ray.t, 1.0, 1e-15);
  EXPECT_FALSE(tree.intersect_ray({0.2, 0.2, -1}, {0, 0, -1}).hit);
  EXPECT_FALSE(tree.intersect_ray({5, 5, 0}, {1, 0, 0}).hit);
}

TEST(GeometryAabbTree, FaceOfSkipsDeletedFaces) {
  mesh::SurfaceMesh m = mesh::make_icosphere(1);
  mesh::Halfedge h = mesh::SurfaceMesh::halfedge(mesh::Edge(0), 0);
  ASSERT_TRUE(m.is_collapse_ok(h));
  m.collapse(h);
  TriangleTree tree;
  tree.build(m);
  EXPECT_EQ(tree.triangles().size(), m.n_faces());
  for (std::uint32_t t = 0; t < tree.triangles().size(); ++t) {
    mesh::Face f = tree.face_of(t);
    ASSERT_FALSE(m.is_deleted(f));
    mesh::Vertex v[3];
    m.face_vertices(f, v);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(tree.triangles()[t][k], v[k].idx);
  }
}

// A plate 0.002 thick: from just below its top, the nearest point is on the top, but among the
// triangles facing down (a vertex of the bottom sheet looking for its own sheet) it is on the
// bottom; against brute force over the facing triangles on random queries.
TEST(GeometryAabbTree, ClosestPointFacingKeepsToItsSheet) {
  const double t = 0.002;
  std::vector<Point> pts;
  for (double x : {0.0, 1.0})
    for (double y : {0.0, 1.0})
      for (double z : {0.0, t}) pts.push_back(Point(x, y, z));
  // Index 4x + 2y + z; every triangle oriented outwards.
  std::vector<std::array<std::uint32_t, 3>> tris = {
      {0, 2, 6}, {0, 6, 4},  // bottom, normal -z
      {1, 5, 7}, {1, 7, 3},  // top, normal +z
      {0, 1, 3}, {0, 3, 2},  // x = 0
      {4, 6, 7}, {4, 7, 5},  // x = 1
      {0, 4, 5}, {0, 5, 1},  // y = 0
      {2, 3, 7}, {2, 7, 6},  // y = 1
  };
  TriangleTree tree;
  tree.build(pts, tris);
  const Point q(0.5, 0.4, 0.0015);
  EXPECT_NEAR(tree.closest_point(q).point.z, t, 1e-12);
  const TriangleTree::ClosestHit down = tree.closest_point_facing(q, Vec3(0, 0, -1));
  ASSERT_NE(down.triangle, UINT32_MAX);
  EXPECT_NEAR(down.point.z, 0.0, 1e-12);
  EXPECT_TRUE(tree.faces(down.triangle, Vec3(0, 0, -1)));
  // A hint on the wrong sheet is ignored, not taken as the answer.
  const TriangleTree::ClosestHit top = tree.closest_point(q);
  const TriangleTree::ClosestHit from_top = tree.closest_point_facing(q, Vec3(0, 0, -1), &top);
  EXPECT_NEAR(from_top.point.z, 0.0, 1e-12);

  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.2, 1.2);
  for (int i = 0; i < 200; ++i) {
    const Point p(u(rng), u(rng), 0.01 * u(rng));
    const Vec3 facing(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
    double best = std::numeric_limits<double>::infinity();
    for (const auto& tri : tree.triangles()) {
      const Point &a = tree.points()[tri[0]], &b = tree.points()[tri[1]], &c = tree.points()[tri[2]];
      if (!(glm::dot(glm::cross(b - a, c - a), facing) > 0)) continue;
      double bary[3];
      const Point cp = closest_point_on_triangle(p, a, b, c, bary);
      best = std::min(best, glm::dot(cp - p, cp - p));
    }
    const TriangleTree::ClosestHit hit = tree.closest_point_facing(p, facing);
    ASSERT_NE(hit.triangle, UINT32_MAX);
    EXPECT_NEAR(hit.distance2, best, 1e-15);
  }
  // Nothing faces the zero vector.
  EXPECT_EQ(tree.closest_point_facing(q, Vec3(0.0)).triangle, UINT32_MAX);
}
