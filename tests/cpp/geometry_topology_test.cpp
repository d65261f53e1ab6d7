// Boundary loops, components, genus and bounding box on meshes of known topology.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "geometry/topology.h"
#include "geometry_test_util.h"
#include "io/load_mesh.h"
#include "mesh/primitives.h"

using namespace adasculpt;
using namespace adasculpt::geometry;

TEST(GeometryTopology, Sphere) {
  mesh::SurfaceMesh m = mesh::make_icosphere(2, 3.0);
  EXPECT_EQ(boundary_loops(m), 0);
  EXPECT_EQ(components(m), 1);
  EXPECT_EQ(genus(m), 0);
  EXPECT_NEAR(bounding_box_diagonal(m), 6.0 * std::sqrt(3.0), 1e-9);
}

TEST(GeometryTopology, GridIsADisc) {
  mesh::SurfaceMesh m = mesh::make_grid(5, 2.0);
  EXPECT_EQ(boundary_loops(m), 1);
  EXPECT_EQ(components(m), 1);
  EXPECT_EQ(genus(m), 0);
  EXPECT_NEAR(bounding_box_diagonal(m), 2.0 * std::sqrt(2.0), 1e-12);
}

TEST(GeometryTopology, CylinderHasTwoBoundaries) {
  mesh::SurfaceMesh m = test::make_cylinder(1.0, 12, 3);
  EXPECT_EQ(boundary_loops(m), 2);
  EXPECT_EQ(genus(m), 0);
}

TEST(GeometryTopology, TwoComponents) {
  io::PolygonSoup a = io::soup_from_mesh(mesh::make_icosphere(1)), b = io::soup_from_mesh(mesh::make_grid(2));
  const auto offset = static_cast<std::uint32_t>(a.points.size());
  a.points.insert(a.points.end(), b.points.begin(), b.points.end());
  for (auto t : b.triangles) a.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  mesh::SurfaceMesh m = mesh::build_from_triangles(a.points, a.triangles);
  EXPECT_EQ(components(m), 2);
  EXPECT_EQ(boundary_loops(m), 1);
  EXPECT_EQ(genus(m), 0);
}

TEST(GeometryTopology, DeletedElementsAreIgnored) {
  mesh::SurfaceMesh m = mesh::make_icosphere(2);
  for (int i = 0; i < 50; ++i) {
    mesh::Halfedge h = mesh::SurfaceMesh::halfedge(mesh::Edge(static_cast<mesh::Index>(7 * i)), 0);
    if (!m.is_deleted(h) && m.is_collapse_ok(h)) m.collapse(h);
  }
  ASSERT_TRUE(m.has_garbage());
  EXPECT_EQ(genus(m), 0);
  EXPECT_EQ(components(m), 1);
}

TEST(GeometryTopology, EightHasGenusTwo) {
  const std::string path = test::test_mesh("eight.off");
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not found";
  mesh::SurfaceMesh m = io::load_mesh(path);
  EXPECT_EQ(boundary_loops(m), 0);
  EXPECT_EQ(components(m), 1);
  EXPECT_EQ(genus(m), 2);
}

TEST(GeometryTopology, HemisphereHasOneBoundary) {
  const std::string path = test::test_mesh("hemisphere.off");
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not found";
  mesh::SurfaceMesh m = io::load_mesh(path);
  EXPECT_EQ(boundary_loops(m), 1);
  EXPECT_EQ(genus(m), 0);
}
