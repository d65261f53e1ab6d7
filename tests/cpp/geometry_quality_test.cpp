// The quality report and the sampled distance on meshes with known figures.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "geometry/quality.h"
#include "geometry_test_util.h"
#include "mesh/build_from_triangles.h"
#include "mesh/primitives.h"

using namespace adasculpt;
using namespace adasculpt::geometry;

namespace {

// A patch of the regular triangular lattice (all triangles equilateral, side `edge`).
mesh::SurfaceMesh make_equilateral_grid(int n, double edge) {
  std::vector<std::array<double, 3>> pts;
  std::vector<std::array<std::uint32_t, 3>> tris;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) pts.push_back({edge * (i + 0.5 * j), edge * j * std::sqrt(3.0) / 2, 0});
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      tris.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
      tris.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return mesh::build_from_triangles(pts, tris);
}

mesh::SurfaceMesh scaled(mesh::SurfaceMesh m, double s) {
  for (mesh::Vertex v : m.vertices()) m.position(v) *= s;
  return m;
}

}  // namespace

TEST(GeometryQuality, EquilateralGrid) {
  QualityReport r = quality_report(make_equilateral_grid(8, 0.5));
  EXPECT_EQ(r.vertices, 81u);
  EXPECT_EQ(r.faces, 128u);
  EXPECT_EQ(r.boundary_loops, 1);
  EXPECT_EQ(r.genus, 0);
  EXPECT_NEAR(r.min_angle_deg, 60, 1e-9);
  EXPECT_NEAR(r.max_angle_deg, 60, 1e-9);
  EXPECT_NEAR(r.mean_min_angle_deg, 60, 1e-9);
  EXPECT_EQ(r.pct_min_angle_lt_30, 0);
  EXPECT_EQ(r.valence_6_pct, 100);
  ASSERT_EQ(r.valence_histogram.size(), 1u);
  EXPECT_EQ(r.valence_histogram.at(6), 49u);  // the 7 x 7 interior vertices
  EXPECT_NEAR(r.edge_length_min, 0.5, 1e-12);
  EXPECT_NEAR(r.edge_length_max, 0.5, 1e-12);
  EXPECT_NEAR(r.edge_length_std, 0.0, 1e-9);
  EXPECT_NEAR(r.area, 128 * 0.25 * std::sqrt(3.0) / 4, 1e-12);
  EXPECT_NEAR(r.edge_length_mean_rel, 0.5 / r.bbox_diag, 1e-12);
  EXPECT_EQ(r.degenerate_faces, 0u);
}

TEST(GeometryQuality, RightTrianglesOfABox) {
  QualityReport r = quality_report(mesh::make_box(2, 2, 2));
  EXPECT_NEAR(r.min_angle_deg, 45, 1e-9);
  EXPECT_NEAR(r.max_angle_deg, 90, 1e-9);
  EXPECT_NEAR(r.mean_min_angle_deg, 45, 1e-9);
  EXPECT_EQ(r.genus, 0);
  EXPECT_NEAR(r.area, 6.0, 1e-12);
}

TEST(GeometryQuality, DegenerateFaceCountsAsZeroDegrees) {
  // A flat fan whose centre sits exactly on an edge of the outline: one zero-area face.
  std::vector<std::array<double, 3>> pts = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {1, 1, 0}};
  mesh::SurfaceMesh m = mesh::build_from_triangles(pts, {{0, 1, 3}, {1, 2, 3}, {0, 2, 1}});
  QualityReport r = quality_report(m);
  EXPECT_EQ(r.degenerate_faces, 1u);
  EXPECT_EQ(r.min_angle_deg, 0);
  EXPECT_NEAR(r.max_angle_deg, 180, 1e-9);
}

TEST(GeometryQuality, JsonKeys) {
  nlohmann::json j = to_json(quality_report(mesh::make_icosphere(1)));
  const std::set<std::string> expected = {
      "vertices", "faces", "edges", "boundary_loops", "components", "genus", "min_angle_deg", "max_angle_deg",
      "mean_min_angle_deg", "pct_min_angle_lt_30", "pct_min_angle_lt_10", "valence_6_pct", "valence_histogram",
      "edge_length_min", "edge_length_mean", "edge_length_max", "edge_length_std", "edge_length_mean_rel",
      "degenerate_faces", "bbox_diag", "area"};
  std::set<std::string> keys;
  for (const auto& item : j.items()) keys.insert(item.key());
  EXPECT_EQ(keys, expected);
  EXPECT_EQ(j["vertices"], 42);
  EXPECT_EQ(j["valence_histogram"]["5"], 12);
  EXPECT_EQ(j["valence_histogram"]["6"], 30);
}

TEST(GeometryQuality, DistanceOfIdenticalMeshesIsZero) {
  mesh::SurfaceMesh m = mesh::make_icosphere(2);
  DistanceReport d = distance_between(m, m, 20000);
  EXPECT_LT(d.hausdorff, 1e-12);
  EXPECT_LT(d.rms, 1e-12);
}

TEST(GeometryQuality, DistanceOfAScaledCube) {
  // Faces 0.005 apart everywhere, corners sqrt(3) * 0.005 apart (as meshq's own test).
  mesh::SurfaceMesh cube = mesh::make_box(1, 1, 1);
  DistanceReport d = distance_between(scaled(cube, 1.01), cube, 50000);
  EXPECT_NEAR(d.hausdorff, 0.005 * std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(d.hausdorff_rel, 0.005, 1e-12);
  EXPECT_GE(d.rms, 0.005 - 1e-12);
  EXPECT_LT(d.rms, 0.00502);
  EXPECT_NEAR(d.rms_rel, d.rms / std::sqrt(3.0), 1e-15);
  // Deterministic: the same call gives bit-identical figures.
  DistanceReport again = distance_between(scaled(cube, 1.01), cube, 50000);
  EXPECT_EQ(again.rms, d.rms);
}

TEST(GeometryQuality, HausdorffDistanceSaysWhereItIsReached) {
  // One vertex of an icosphere pushed out: the distance is reached at that vertex, on the mesh,
  // and its closest point on the reference is under it; swapped, on the reference's side.
  mesh::SurfaceMesh sphere = mesh::make_icosphere(2);
  mesh::SurfaceMesh bumped = sphere;
  const mesh::Vertex tip(7);
  bumped.position(tip) *= 1.2;
  DistanceReport d = distance_between(bumped, sphere, 20000);
  EXPECT_FALSE(d.hausdorff_on_reference);
  EXPECT_EQ(d.hausdorff_at, bumped.position(tip));
  EXPECT_NEAR(glm::length(d.hausdorff_at - d.hausdorff_closest), d.hausdorff, 1e-12);
  EXPECT_LT(glm::length(d.hausdorff_closest - sphere.position(tip)), 0.2 * d.hausdorff);
  DistanceReport swapped = distance_between(sphere, bumped, 20000);
  EXPECT_TRUE(swapped.hausdorff_on_reference);
  EXPECT_EQ(swapped.hausdorff_at, bumped.position(tip));
  EXPECT_DOUBLE_EQ(swapped.hausdorff, d.hausdorff);
}
