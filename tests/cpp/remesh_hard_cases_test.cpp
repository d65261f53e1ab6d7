// Coarse CAD-like inputs (issue 17, item 2): long needle triangles, fans of valence 31, sharp
// edges and genus 2, the kind of mesh a CAD exporter writes. The remesher must keep the topology,
// create no crossing triangles and stay within its vertex budget, at fine and coarse settings.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "geometry/quality.h"
#include "geometry/self_intersections.h"
#include "geometry/topology.h"
#include "mesh/build_from_triangles.h"
#include "remesh/remesher.h"

using namespace adasculpt;
using mesh::SurfaceMesh;

namespace {

// A 4 x 2 x 0.4 plate with two round holes of radius 0.5 (48 segments each), triangulated as CAD
// exporters do: each half of the top and bottom faces is the ring between a square and its hole,
// fanned from the square's four corners (valence 17 at a corner, 31 where the halves meet), and
// the walls are single quads split into two needles. 204 vertices, mean smallest angle 7 degrees.
SurfaceMesh cad_plate_with_two_holes() {
  constexpr int kSegments = 48;
  constexpr double kThickness = 0.4, kRadius = 0.5, kPi = 3.14159265358979323846;
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  auto add = [&](double x, double y, double z) {
    points.push_back({x, y, z});
    return static_cast<std::uint32_t>(points.size() - 1);
  };
  // The outline, counter-clockwise seen from above; top (z = thickness) and bottom corners.
  const double outline[6][2] = {{0, 0}, {2, 0}, {4, 0}, {4, 2}, {2, 2}, {0, 2}};
  std::uint32_t top[6], bottom[6];
  for (int i = 0; i < 6; ++i) {
    top[i] = add(outline[i][0], outline[i][1], kThickness);
    bottom[i] = add(outline[i][0], outline[i][1], 0);
  }
  // Each half: its square's corners (indices into the outline) counter-clockwise from (x0, 0).
  const int square[2][4] = {{0, 1, 4, 5}, {1, 2, 3, 4}};
  for (int s = 0; s < 2; ++s) {
    const double cx = 1.0 + 2.0 * s, cy = 1.0;
    std::uint32_t ring_top[kSegments], ring_bottom[kSegments];
    for (int j = 0; j < kSegments; ++j) {
      const double a = 2 * kPi * j / kSegments;
      ring_top[j] = add(cx + kRadius * std::cos(a), cy + kRadius * std::sin(a), kThickness);
      ring_bottom[j] = add(cx + kRadius * std::cos(a), cy + kRadius * std::sin(a), 0);
    }
    // Corner k (at 225, 315, 45, 135 degrees) takes the hole's segments between the directions
    // of its two sides (270, 0, 90, 180 degrees); side k takes the hole's point in its direction.
    const int side_point[4] = {3 * kSegments / 4, 0, kSegments / 4, kSegments / 2};
    for (int k = 0; k < 4; ++k) {
      const int c = square[s][k], next = square[s][(k + 1) % 4];
      for (int j = side_point[(k + 3) % 4]; j != side_point[k]; j = (j + 1) % kSegments) {
        const int jn = (j + 1) % kSegments;
        triangles.push_back({top[c], ring_top[jn], ring_top[j]});
        triangles.push_back({bottom[c], ring_bottom[j], ring_bottom[jn]});
      }
      const int m = side_point[k];
      triangles.push_back({top[c], top[next], ring_top[m]});
      triangles.push_back({bottom[next], bottom[c], ring_bottom[m]});
    }
    for (int j = 0; j < kSegments; ++j) {  // the hole's wall, facing its axis
      const int jn = (j + 1) % kSegments;
      triangles.push_back({ring_bottom[jn], ring_bottom[j], ring_top[j]});
      triangles.push_back({ring_bottom[jn], ring_top[j], ring_top[jn]});
    }
  }
  for (int i = 0; i < 6; ++i) {  // the outer walls, one quad each
    const int n = (i + 1) % 6;
    triangles.push_back({bottom[i], bottom[n], top[n]});
    triangles.push_back({bottom[i], top[n], top[i]});
  }
  return mesh::build_from_triangles(points, triangles);
}

remesh::RemeshOptions setting(const SurfaceMesh& m, bool adaptive, double pct, double features) {
  remesh::RemeshOptions o = remesh::default_options_for(m);
  o.adaptive = adaptive;
  const double d = remesh::bounding_box_diagonal(m);
  (adaptive ? o.epsilon : o.target_length) = pct * 0.01 * d;
  o.feature_angle_deg = features;
  return o;
}

}  // namespace

TEST(RemeshHardCases, GeneratedCadPlateIsTheCoarseNeedleInputOfTheIssue) {
  const SurfaceMesh input = cad_plate_with_two_holes();
  ASSERT_NO_THROW(input.validate());
  const geometry::QualityReport q = geometry::quality_report(input);
  EXPECT_EQ(q.genus, 2);
  EXPECT_LT(q.mean_min_angle_deg, 10.0);
  EXPECT_EQ(q.valence_histogram.rbegin()->first, 31);
  EXPECT_TRUE(geometry::self_intersections(input).pairs.empty());
}

TEST(RemeshHardCases, CoarseCadPlateStaysCrossingFreeBoundedAndWellShaped) {
  const SurfaceMesh input = cad_plate_with_two_holes();
  struct Case {
    bool adaptive;
    double pct, features;
  };
  for (const Case c : {Case{true, 0.5, 0}, Case{true, 2, 0}, Case{true, 0.5, 45}, Case{false, 2, 0},
                       Case{false, 8, 45}}) {
    SCOPED_TRACE((c.adaptive ? "epsilon " : "length ") + std::to_string(c.pct) + "% features " +
                 std::to_string(c.features));
    SurfaceMesh m = input;
    const remesh::RemeshReport r = remesh::remesh(m, setting(input, c.adaptive, c.pct, c.features));
    ASSERT_NO_THROW(m.validate());
    EXPECT_TRUE(r.warning.empty()) << r.warning;
    EXPECT_LE(double(m.n_vertices()), 2.0 * r.estimated_vertices + 500);
    EXPECT_EQ(geometry::genus(m), 2);
    EXPECT_EQ(geometry::components(m), 1);
    EXPECT_EQ(geometry::self_intersections(m, 100).pairs.size(), 0u);
    EXPECT_GE(geometry::quality_report(m).min_angle_deg, 25.0);
  }
}
