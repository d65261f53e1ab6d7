// Discrete curvature and normals on surfaces whose curvature is known.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "geometry/curvature.h"
#include "geometry/normals.h"
#include "geometry/triangle.h"
#include "geometry_test_util.h"
#include "mesh/build_from_triangles.h"
#include "mesh/primitives.h"

using namespace adasculpt;
using namespace adasculpt::geometry;

TEST(GeometryCurvature, SphereIsOneOverRadius) {
  for (double r : {0.5, 3.0}) {
    mesh::SurfaceMesh m = mesh::make_icosphere(4, r);
    std::vector<double> k;
    max_abs_curvature(m, k);
    ASSERT_EQ(k.size(), m.vertices_size());
    for (mesh::Vertex v : m.vertices()) EXPECT_NEAR(k[v.idx] * r, 1.0, 0.02);
  }
}

TEST(GeometryCurvature, MixedAreasTileTheSurface) {
  mesh::SurfaceMesh m = mesh::make_box(3, 2, 5, 1.0, 2.0, 0.5);
  double faces = 0, vertices = 0;
  for (mesh::Face f : m.faces()) faces += face_area(m, f);
  for (mesh::Vertex v : m.vertices()) vertices += mixed_voronoi_area(m, v);
  EXPECT_NEAR(vertices, faces, 1e-12);
}

TEST(GeometryCurvature, PlaneIsFlat) {
  mesh::SurfaceMesh m = mesh::make_grid(10, 3.0);
  for (mesh::Vertex v : m.vertices()) {
    EXPECT_NEAR(max_abs_curvature(m, v), 0.0, 1e-9);
    if (!m.is_boundary(v)) {
      EXPECT_NEAR(glm::length(cotan_laplacian(m, v)), 0.0, 1e-12);
    }
  }
}

// A fan around one vertex whose ring waves up and down (a monkey saddle): the angles around the
// centre add up to between 2 pi and 5 pi depending on the wave's height. max_abs_curvature sums the
// angles as complex arguments, counting turns; this checks it against one atan2 per corner.
TEST(GeometryCurvature, SaddleAngleSumsPastTwoTurnsMatchPerCornerAngles) {
  const int n = 24;
  for (double height : {0.0, 0.3, 1.0, 3.0, 10.0, 40.0}) {
    for (int waves : {2, 3, 5}) {
      std::vector<std::array<double, 3>> points{{0, 0, 0}};
      std::vector<std::array<std::uint32_t, 3>> triangles;
      for (int k = 0; k < n; ++k) {
        const double t = 2 * M_PI * k / n;
        points.push_back({std::cos(t), std::sin(t), height * std::sin(waves * t)});
        triangles.push_back({0, std::uint32_t(1 + k), std::uint32_t(1 + (k + 1) % n)});
      }
      const mesh::SurfaceMesh m = mesh::build_from_triangles(points, triangles);
      const mesh::Vertex c(0);
      ASSERT_FALSE(m.is_boundary(c));
      double angles = 0;
      for (mesh::Halfedge h : m.halfedges(c)) {
        const Vec3 u = m.position(m.to_vertex(h)) - m.position(c);
        const Vec3 w = m.position(m.to_vertex(m.next(h))) - m.position(c);
        angles += std::atan2(glm::length(glm::cross(u, w)), glm::dot(u, w));
      }
      const double area = mixed_voronoi_area(m, c);
      const double mean = glm::length(cotan_laplacian(m, c)) / (4 * area);
      const double gauss = (2 * M_PI - angles) / area;
      const double expected = mean + std::sqrt(std::max(mean * mean - gauss, 0.0));
      EXPECT_NEAR(max_abs_curvature(m, c), expected, 1e-9 * (1 + expected)) << "height " << height << ", waves " << waves
                                                                           << ", angle sum " << angles / M_PI << " pi";
      if (height == 40.0 && waves == 5) {
        EXPECT_GT(angles, 4 * M_PI);  // the case has more than two turns
      }
    }
  }
}

TEST(GeometryCurvature, CylinderIsOneOverRadius) {
  const double r = 2.0;
  mesh::SurfaceMesh m = test::make_cylinder(r, 64, 10);
  int interior = 0;
  for (mesh::Vertex v : m.vertices()) {
    if (m.is_boundary(v)) {
      EXPECT_EQ(max_abs_curvature(m, v), 0.0);
      continue;
    }
    ++interior;
    EXPECT_NEAR(max_abs_curvature(m, v) * r, 1.0, 0.02);
  }
  EXPECT_GT(interior, 0);
}

TEST(GeometryNormals, SphereNormalsPointOutwards) {
  mesh::SurfaceMesh m = mesh::make_icosphere(3, 2.0);
  std::vector<Vec3> n;
  vertex_normals(m, n);
  for (mesh::Vertex v : m.vertices()) EXPECT_GT(glm::dot(n[v.idx], glm::normalize(m.position(v))), 0.999);
}

TEST(GeometryNormals, BoxCornerIsTheDiagonal) {
  // Angle weighting makes a cube corner's normal the diagonal whatever the triangulation.
  mesh::SurfaceMesh m = mesh::make_box(1, 1, 1);
  for (mesh::Vertex v : m.vertices()) {
    Vec3 n = vertex_normal(m, v);
    EXPECT_NEAR(glm::dot(n, glm::normalize(m.position(v))), 1.0, 1e-12);
  }
}
