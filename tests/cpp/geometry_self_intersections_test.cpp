// Exact predicates and the self-intersection counter: against integer arithmetic, hand-built
// configurations for every adjacency rule, brute force over all pairs, and the counts the
// independent judge (meshq, CGAL) reports for the shared meshes.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <set>

#include "geometry/exact_predicates.h"
#include "geometry/self_intersections.h"
#include "geometry_test_util.h"
#include "io/load_mesh.h"
#include "mesh/primitives.h"

using namespace adasculpt;
using namespace adasculpt::geometry;

namespace {

using Int = __int128;
int sign128(Int x) { return (x > 0) - (x < 0); }

// The exact orient3d of integer points (coordinates below 2^30: the determinant fits).
int orient3d_int(const std::array<std::int64_t, 3>& a, const std::array<std::int64_t, 3>& b,
                 const std::array<std::int64_t, 3>& c, const std::array<std::int64_t, 3>& d) {
  Int u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k) u[k] = b[k] - a[k], v[k] = c[k] - a[k], w[k] = d[k] - a[k];
  return sign128(u[0] * (v[1] * w[2] - v[2] * w[1]) + u[1] * (v[2] * w[0] - v[0] * w[2]) +
                 u[2] * (v[0] * w[1] - v[1] * w[0]));
}

Point to_point(const std::array<std::int64_t, 3>& p, double unit) {
  return Point(double(p[0]) * unit, double(p[1]) * unit, double(p[2]) * unit);
}

std::vector<Point> corners(std::initializer_list<Point> list) { return std::vector<Point>(list); }

}  // namespace

TEST(ExactPredicates, Orient3dMatchesIntegerArithmeticOnNearlyCoplanarPoints) {
  // Points near a plane through three random points, with coordinates up to 2^29: products
  // exceed 53 bits, so the plain double determinant is often wrong in sign or zero-ness.
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<std::int64_t> coord(-(1 << 29), 1 << 29), small(-1, 1), t(-2, 2);
  int exact_zero = 0, checked = 0;
  for (int i = 0; i < 20000; ++i) {
    std::array<std::int64_t, 3> a{coord(rng), coord(rng), coord(rng)};
    std::array<std::int64_t, 3> b{coord(rng) / 64, coord(rng) / 64, coord(rng) / 64};
    std::array<std::int64_t, 3> c{coord(rng) / 64, coord(rng) / 64, coord(rng) / 64};
    for (int k = 0; k < 3; ++k) b[k] += a[k] / 2, c[k] += a[k] / 2;
    const std::int64_t s = t(rng), r = t(rng);
    std::array<std::int64_t, 3> d;
    for (int k = 0; k < 3; ++k) d[k] = a[k] + s * (b[k] - a[k]) + r * (c[k] - a[k]) + small(rng);
    bool in_range = true;
    for (auto x : d) in_range = in_range && x > -(1LL << 31) && x < (1LL << 31);
    if (!in_range) continue;
    const int expected = orient3d_int(a, b, c, d);
    // A power-of-two unit keeps every coordinate exactly representable.
    const double unit = 0x1.0p-20;
    ASSERT_EQ(orient3d(to_point(a, unit), to_point(b, unit), to_point(c, unit), to_point(d, unit)), expected) << i;
    exact_zero += expected == 0;
    ++checked;
  }
  EXPECT_GT(checked, 10000);
  EXPECT_GT(exact_zero, 50);  // the exactly coplanar case was exercised
}

TEST(ExactPredicates, Orient2dOnNearlyCollinearPoints) {
  // Shewchuk's classic: points a few ulps off the line through (12,12) and (24,24).
  const double base = 0.5;
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 64; ++j) {
      const double x = base + i * 0x1.0p-53, y = base + j * 0x1.0p-53;
      // (x,y), (12,12), (24,24) turn counter-clockwise iff (x,y) lies above the line y = x
      const int expected = (j > i) - (j < i);
      EXPECT_EQ(orient2d(x, y, 12, 12, 24, 24), expected) << i << " " << j;
    }
}

TEST(TriangleIntersection, SeparatedPiercingTouchingAndCoplanar) {
  const Point p[3] = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}};
  auto q_of = [](Point a, Point b, Point c) { return std::array<Point, 3>{a, b, c}; };
  struct Case {
    std::array<Point, 3> q;
    bool expected;
    const char* what;
  };
  const Case cases[] = {
      {q_of({1, 1, 1}, {2, 1, 1}, {1, 2, 1}), false, "parallel plane above"},
      {q_of({1, 1, -1}, {1, 1, 1}, {5, 5, 0}), true, "edge pierces the interior"},
      {q_of({1, 1, 0}, {1, 1, 1}, {2, 2, 1}), true, "vertex touches the interior"},
      {q_of({2, 2, 0}, {2, 2, 1}, {3, 3, 1}), true, "vertex touches the hypotenuse"},
      {q_of({2.01, 2.01, 0}, {2.01, 2.01, 1}, {3, 3, 1}), false, "vertex just past the hypotenuse"},
      {q_of({-1, 1, -1}, {-1, 1, 1}, {1, 1, 0}), true, "edges cross at a point of p's interior"},
      {q_of({1, 1, 0}, {2, 1, 0}, {1, 2, 0}), true, "coplanar, inside"},
      {q_of({-1, -1, 0}, {5, -1, 0}, {-1, 5, 0}), true, "coplanar, containing"},
      {q_of({3, 3, 0}, {5, 3, 0}, {3, 5, 0}), false, "coplanar, disjoint"},
      {q_of({4, 0, 0}, {6, 0, 0}, {6, 2, 0}), true, "coplanar, touching at a corner"},
      {q_of({-1, 2, 0}, {1, 2, 0}, {0, 6, 0}), true, "coplanar, edges crossing"},
      {q_of({5, 5, -1}, {5, 5, 1}, {6, 6, 0}), false, "non-coplanar, apart"},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(triangles_intersect(p, c.q.data()), c.expected) << c.what;
    EXPECT_EQ(triangles_intersect(c.q.data(), p), c.expected) << c.what << " (swapped)";
  }
}

TEST(TriangleIntersection, SegmentAgainstTriangle) {
  const Point t[3] = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}};
  EXPECT_TRUE(segment_intersects_triangle({1, 1, -1}, {1, 1, 1}, t));
  EXPECT_TRUE(segment_intersects_triangle({1, 1, 0}, {1, 1, 1}, t));    // endpoint on the face
  EXPECT_FALSE(segment_intersects_triangle({1, 1, 0.5}, {1, 1, 1}, t));  // above it
  EXPECT_TRUE(segment_intersects_triangle({-1, 1, 0}, {1, 1, 0}, t));   // in its plane, crossing an edge
  EXPECT_FALSE(segment_intersects_triangle({-2, 1, 0}, {-1, 1, 0}, t));  // in its plane, outside
  EXPECT_TRUE(collinear({0, 0, 0}, {1, 1, 1}, {3, 3, 3}));
  EXPECT_FALSE(collinear({0, 0, 0}, {1, 1, 1}, {3, 3, 3.0000000001}));
}

TEST(FacesIntersect, SharedEdgeCountsOnlyWhenFolded) {
  // p=0, q=1 shared; triangle 0-1-2 and a second face 1-0-3 (consistently oriented).
  auto pts = corners({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}});
  EXPECT_FALSE(faces_intersect(pts, {0, 1, 2}, {1, 0, 3})) << "flat, unfolded";
  pts[3] = {0.3, -1, 0.5};
  EXPECT_FALSE(faces_intersect(pts, {0, 1, 2}, {1, 0, 3})) << "a dihedral angle";
  pts[3] = {0.5, 0.2, 0};
  EXPECT_TRUE(faces_intersect(pts, {0, 1, 2}, {1, 0, 3})) << "folded flat onto the first";
  pts[3] = {0.5, 0.2, 1e-300};
  EXPECT_FALSE(faces_intersect(pts, {0, 1, 2}, {1, 0, 3})) << "folded, but not exactly coplanar";
}

TEST(FacesIntersect, SharedVertexCountsOnlyWhenMeetingElsewhere) {
  auto pts = corners({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {-2, 0, 0.5}, {-1, -2, 0.5}});
  EXPECT_FALSE(faces_intersect(pts, {0, 1, 2}, {0, 3, 4})) << "fan neighbours apart";
  pts[3] = {1, 0.5, -1};
  pts[4] = {1, 0.5, 1};
  EXPECT_TRUE(faces_intersect(pts, {0, 1, 2}, {0, 3, 4})) << "opposite edge pierces the first face";
  pts[3] = {0.5, 0.2, 0};
  pts[4] = {0.2, 0.5, 0};
  EXPECT_TRUE(faces_intersect(pts, {0, 1, 2}, {0, 3, 4})) << "coplanar, inside the first face's corner";
  pts[3] = {-1, 0, 0};
  pts[4] = {0, -1, 0};
  EXPECT_FALSE(faces_intersect(pts, {0, 1, 2}, {0, 3, 4})) << "coplanar, opposite corner";
}

namespace {

// All intersecting pairs by testing every pair (reference for the tree's broad phase).
using PairSet = std::set<std::pair<std::uint32_t, std::uint32_t>>;

PairSet brute_force_pairs(
    const std::vector<Point>& pts, const std::vector<std::array<std::uint32_t, 3>>& tris) {
  PairSet out;
  for (std::uint32_t i = 0; i < tris.size(); ++i) {
    if (collinear(pts[tris[i][0]], pts[tris[i][1]], pts[tris[i][2]])) continue;
    for (std::uint32_t j = i + 1; j < tris.size(); ++j) {
      if (collinear(pts[tris[j][0]], pts[tris[j][1]], pts[tris[j][2]])) continue;
      if (faces_intersect(pts, tris[i], tris[j])) out.insert({i, j});
    }
  }
  return out;
}

void soup_of(const mesh::SurfaceMesh& m, const Vec3& offset, std::vector<Point>& pts,
             std::vector<std::array<std::uint32_t, 3>>& tris) {
  const std::uint32_t base = static_cast<std::uint32_t>(pts.size());
  for (mesh::Vertex v : m.vertices()) pts.push_back(m.position(v) + offset);
  for (mesh::Face f : m.faces()) {
    mesh::Vertex v[3];
    m.face_vertices(f, v);
    tris.push_back({base + v[0].idx, base + v[1].idx, base + v[2].idx});
  }
}

}  // namespace

TEST(SelfIntersections, CleanMeshesHaveNone) {
  EXPECT_TRUE(self_intersections(mesh::make_icosphere(4)).pairs.empty());
  EXPECT_TRUE(self_intersections(mesh::make_grid(30)).pairs.empty());  // exactly coplanar neighbours
  EXPECT_TRUE(self_intersections(mesh::make_box(6, 5, 4)).pairs.empty());
  EXPECT_TRUE(self_intersections(test::make_cylinder(1, 40, 20)).pairs.empty());
}

TEST(SelfIntersections, TreeFindsExactlyTheBruteForcePairs) {
  // Two overlapping spheres plus a jittered one: crossings along two curves and many
  // near-misses, every pair checked against the quadratic reference.
  std::vector<Point> pts;
  std::vector<std::array<std::uint32_t, 3>> tris;
  soup_of(mesh::make_icosphere(2), Vec3(0), pts, tris);
  soup_of(mesh::make_icosphere(2, 0.8), Vec3(0.9, 0.1, 0.05), pts, tris);
  mesh::SurfaceMesh crumpled = mesh::make_icosphere(2);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.12, 0.12);
  for (mesh::Vertex v : crumpled.vertices())
    crumpled.position(v) += Vec3(jitter(rng), jitter(rng), jitter(rng));
  soup_of(crumpled, Vec3(-1.5, 0, 0), pts, tris);
  const auto expected = brute_force_pairs(pts, tris);
  const SelfIntersectionReport got = self_intersections(pts, tris);
  EXPECT_GT(expected.size(), 100u);
  EXPECT_FALSE(got.capped);
  EXPECT_EQ(PairSet(got.pairs.begin(), got.pairs.end()), expected);
  EXPECT_EQ(got.pairs.size(), expected.size()) << "no pair reported twice";

  const SelfIntersectionReport capped = self_intersections(pts, tris, 10);
  EXPECT_TRUE(capped.capped);
  EXPECT_EQ(capped.pairs.size(), 10u);
}

TEST(SelfIntersections, DegenerateFacesAreLeftOutAndCounted) {
  auto pts = corners({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 0, -1}, {1, 0, 1}});
  // A collinear face 0-1-2, a face 0-2-3 containing it, and a face piercing both.
  const std::vector<std::array<std::uint32_t, 3>> tris = {{0, 1, 2}, {0, 2, 3}, {4, 5, 3}};
  const SelfIntersectionReport r = self_intersections(pts, tris);
  EXPECT_EQ(r.degenerate_faces, 1u);
  ASSERT_EQ(r.pairs.size(), 1u);  // the piercing face shares vertex 3 with face 1 and crosses it
  EXPECT_EQ(r.pairs[0], (std::pair<std::uint32_t, std::uint32_t>(1, 2)));
}

TEST(SelfIntersections, SharedMeshesMatchMeshq) {
  // SI pairs from ../shared/meshes/README.md (meshq --stats, CGAL exact predicates).
  const std::pair<const char*, size_t> table[] = {
      {"bunny.off", 2}, {"horse.off", 4}, {"dragon.off", 29}, {"fandisk.off", 0}, {"rocker_arm.off", 0},
      {"face.off", 0},  {"eight.off", 0}, {"hemisphere.off", 0}};
  int found = 0;
  for (const auto& [name, pairs] : table) {
    const std::string path = test::shared_mesh(name);
    if (!std::filesystem::exists(path)) continue;
    ++found;
    EXPECT_EQ(self_intersections(io::load_mesh(path)).pairs.size(), pairs) << name;
  }
  if (found == 0) GTEST_SKIP() << test::shared_mesh("") << " not found";
}
