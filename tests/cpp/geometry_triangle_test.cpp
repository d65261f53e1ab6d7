// Per-triangle geometry: angles, cotangents, normals, areas and the closest point in each
// of the seven Voronoi regions of a triangle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "geometry/triangle.h"
#include "geometry_test_util.h"
#include "mesh/primitives.h"

using namespace adasculpt;
using namespace adasculpt::geometry;

namespace {
using test::kPi;
double deg(double rad) { return rad * 180.0 / kPi; }
}  // namespace

TEST(GeometryTriangle, AnglesOfKnownTriangles) {
  double a[3];
  triangle_angles({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, a);
  EXPECT_NEAR(deg(a[0]), 90, 1e-12);
  EXPECT_NEAR(deg(a[1]), 45, 1e-12);
  EXPECT_NEAR(deg(a[2]), 45, 1e-12);
  triangle_angles({0, 0, 0}, {1, 0, 0}, {0.5, std::sqrt(3.0) / 2, 0}, a);
  for (double x : a) EXPECT_NEAR(deg(x), 60, 1e-12);
  triangle_angles({0, 0, 0}, {std::sqrt(3.0), 0, 0}, {0, 1, 0}, a);  // 30-60-90
  EXPECT_NEAR(deg(a[0]), 90, 1e-12);
  EXPECT_NEAR(deg(a[1]), 30, 1e-12);
  EXPECT_NEAR(deg(a[2]), 60, 1e-12);
  // A sliver: acos would lose precision here, atan2 keeps it.
  triangle_angles({0, 0, 0}, {1, 0, 0}, {0.5, 1e-9, 0}, a);
  EXPECT_NEAR(a[0], 2e-9, 1e-20);
  EXPECT_NEAR(a[0] + a[1] + a[2], kPi, 1e-12);
  // Degenerate: collinear and coincident corners stay finite.
  triangle_angles({0, 0, 0}, {1, 0, 0}, {2, 0, 0}, a);
  EXPECT_NEAR(a[1], kPi, 1e-15);
  triangle_angles({1, 1, 1}, {1, 1, 1}, {1, 1, 1}, a);
  for (double x : a) EXPECT_TRUE(std::isfinite(x));
}

TEST(GeometryTriangle, Cotan) {
  EXPECT_NEAR(cotan({1, 0, 0}, {0, 1, 0}), 0.0, 1e-15);
  EXPECT_NEAR(cotan({1, 0, 0}, {1, 1, 0}), 1.0, 1e-15);
  EXPECT_NEAR(cotan({1, 0, 0}, {-1, 1, 0}), -1.0, 1e-15);
  EXPECT_NEAR(cotan({2, 0, 0}, {1, std::sqrt(3.0), 0}), 1 / std::sqrt(3.0), 1e-15);
  EXPECT_EQ(cotan({1, 0, 0}, {2, 0, 0}), kMaxCotan);
  EXPECT_EQ(cotan({1, 0, 0}, {-2, 0, 0}), -kMaxCotan);
  EXPECT_EQ(cotan({0, 0, 0}, {1, 0, 0}), 0.0);
}

TEST(GeometryTriangle, NormalAndArea) {
  mesh::SurfaceMesh grid = mesh::make_grid(2, 2.0);
  for (mesh::Face f : grid.faces()) {
    Vec3 n = face_normal(grid, f);
    EXPECT_NEAR(std::abs(n.z), 1.0, 1e-15);
    EXPECT_NEAR(face_area(grid, f), 0.5, 1e-15);
  }
}

TEST(GeometryTriangle, ClosestPointInEveryRegion) {
  const Point a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  struct Case {
    Point p;
    double bary[3];
  };
  const Case cases[] = {
      {{-1, -1, 1}, {1, 0, 0}},        // corner a
      {{3, -0.5, -1}, {0, 1, 0}},      // corner b
      {{-0.5, 3, 2}, {0, 0, 1}},       // corner c
      {{0.5, -1, 1}, {0.75, 0.25, 0}}, // edge ab
      {{-1, 1.5, 0}, {0.25, 0, 0.75}}, // edge ac
      {{2, 2, 0.5}, {0, 0.5, 0.5}},    // edge bc
      {{0.5, 0.5, 3}, {0.5, 0.25, 0.25}},  // face
  };
  for (const Case& k : cases) {
    double bary[3];
    Point q = closest_point_on_triangle(k.p, a, b, c, bary);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(bary[i], k.bary[i], 1e-14) << "region of " << k.p.x << "," << k.p.y;
    Point r = test::brute_closest_on_triangle(k.p, a, b, c);
    EXPECT_NEAR(glm::length(q - r), 0.0, 1e-14);
    EXPECT_NEAR(glm::length(q - (bary[0] * a + bary[1] * b + bary[2] * c)), 0.0, 1e-14);
  }
}

TEST(GeometryTriangle, ClosestPointRandomAgainstBruteForce) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int i = 0; i < 10000; ++i) {
    Point a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng)), p(u(rng), u(rng), u(rng));
    if (i % 10 == 0) c = a + 0.3 * (b - a);  // degenerate (collinear) triangles too
    if (i % 17 == 0) b = a;
    if (i % 13 == 0) c = a + 0.3 * (b - a) + 1e-7 * Vec3(u(rng), u(rng), u(rng));  // slivers
    double bary[3];
    Point q = closest_point_on_triangle(p, a, b, c, bary);
    Point r = test::brute_closest_on_triangle(p, a, b, c);
    ASSERT_NEAR(glm::length(q - p), glm::length(r - p), 1e-12);
    ASSERT_NEAR(bary[0] + bary[1] + bary[2], 1.0, 1e-12);
    for (double w : bary) ASSERT_GE(w, -1e-12);
  }
}

// detour_bound (the fidelity check's bound of an edge by a path over a reference corner): every
// point of ab lies within it of the path a -> c -> b, whatever the triangle's shape (obtuse at a or
// b, nearly flat, c near the line).
TEST(GeometryTriangle, DetourBoundHoldsForEveryPointOfTheChord) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int i = 0; i < 5000; ++i) {
    Point a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    if (i % 7 == 0) c = a + 0.4 * (b - a) + 1e-3 * Vec3(u(rng), u(rng), u(rng));  // nearly on the chord
    if (i % 11 == 0) c = a + 2.5 * (b - a) + 0.1 * Vec3(u(rng), u(rng), u(rng));  // far beyond b
    const double bound = detour_bound(a, c, b);
    double farthest = 0;
    for (int k = 0; k <= 200; ++k) {
      const Point p = a + (k / 200.0) * (b - a);
      farthest = std::max(farthest, std::min(glm::length(p - closest_point_on_segment(p, a, c)),
                                             glm::length(p - closest_point_on_segment(p, c, b))));
    }
    ASSERT_LE(farthest, bound * (1 + 1e-12) + 1e-15) << "case " << i;
  }
  // A right angle at c, 1 over the chord: the bound is that height; the chord's midpoint lies
  // 0.71 from the sides.
  EXPECT_NEAR(detour_bound({0, 0, 0}, {1, 1, 0}, {2, 0, 0}), 1.0, 1e-15);
}
