// Discrete curvature and normals on surfaces whose curvature is known.
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/curvature.h"
#include "geometry/normals.h"
#include "geometry/triangle.h"
#include "geometry_test_util.h"
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
