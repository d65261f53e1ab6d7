// The smallest angle feature lines force (remesh/feature_sectors.h): the sweep judges a remesh's
// minimum angle against it, so a wrong sector would excuse real slivers or fail good meshes.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "mesh/build_from_triangles.h"
#include "mesh/primitives.h"
#include "remesh/feature_sectors.h"

using namespace adasculpt;
using mesh::SurfaceMesh;

namespace {

// A flat fan around the origin whose rim is the boundary: n triangles over `span` degrees (360
// closes it into a disc). Its rim's corners are where the boundary turns.
SurfaceMesh flat_fan(int n, double span_deg) {
  std::vector<std::array<double, 3>> points{{0, 0, 0}};
  std::vector<std::array<std::uint32_t, 3>> triangles;
  const bool closed = span_deg >= 360;
  const int rim = closed ? n : n + 1;
  for (int i = 0; i < rim; ++i) {
    const double a = span_deg * M_PI / 180 * i / n;
    points.push_back({std::cos(a), std::sin(a), 0});
  }
  for (int i = 0; i < n; ++i)
    triangles.push_back({0u, static_cast<std::uint32_t>(1 + i), static_cast<std::uint32_t>(1 + (i + 1) % rim)});
  return mesh::build_from_triangles(points, triangles);
}

}  // namespace

TEST(FeatureSectors, ClosedSmoothMeshHasNone) {
  const SurfaceMesh sphere = mesh::make_icosphere(3);
  for (double angle : {0.0, 45.0}) {
    const remesh::FeatureSector s = remesh::smallest_feature_sector(sphere, remesh::feature_edge_marks(sphere, angle));
    EXPECT_EQ(s.angle_deg, 360) << "features " << angle;
    EXPECT_FALSE(s.vertex.is_valid());
  }
}

TEST(FeatureSectors, CubeCornersAreRightAnglesOnlyWithFeaturesOn) {
  const SurfaceMesh box = mesh::make_box(3, 3, 3);
  EXPECT_EQ(remesh::smallest_feature_sector(box, remesh::feature_edge_marks(box, 0)).angle_deg, 360);
  const remesh::FeatureSector s = remesh::smallest_feature_sector(box, remesh::feature_edge_marks(box, 45));
  // Three sharp edges at each corner, 90 degrees apart (along an edge: 180 on both sides).
  EXPECT_NEAR(s.angle_deg, 90, 1e-9);
}

TEST(FeatureSectors, BoundaryCornerIsTheSumOfItsFaceCorners) {
  // A 30-degree wedge of three faces: its apex is a boundary corner of 30 degrees (the sum of
  // three 10-degree corners), its two rim ends 85 degrees each.
  const SurfaceMesh wedge = flat_fan(3, 30);
  const remesh::FeatureSector s = remesh::smallest_feature_sector(wedge, remesh::feature_edge_marks(wedge, 0));
  EXPECT_NEAR(s.angle_deg, 30, 1e-9);
  EXPECT_EQ(s.vertex.idx, 0u);
}

TEST(FeatureSectors, BoundaryGapIsNoSector) {
  // A 350-degree fan of 10-degree triangles: the apex's two boundary edges are 10 degrees apart
  // across the gap, which has no faces and forces nothing; through the faces they are 350 apart.
  // The smallest sector is at the rim's two ends: 85 degrees.
  const SurfaceMesh fan = flat_fan(35, 350);
  const remesh::FeatureSector s = remesh::smallest_feature_sector(fan, remesh::feature_edge_marks(fan, 0));
  EXPECT_NEAR(s.angle_deg, 85, 1e-9);
  EXPECT_NE(s.vertex.idx, 0u);
}
