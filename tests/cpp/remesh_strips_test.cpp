// Strips between creases (remesh/strips.cpp): a flat ring 0.02 wide between two sharp circles,
// the step of a coarse CAD cylinder. Triangles as long as the sizing cannot fit between the two
// circles, and every vertex on them is held there, so the sizing must come down to the ring's
// width. (The same shape on cgal/rotor.off left 16-degree triangles at epsilon 0.5 %.)
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/quality.h"
#include "geometry/self_intersections.h"
#include "mesh/build_from_triangles.h"
#include "remesh/remesher.h"

using namespace adasculpt;
using mesh::SurfaceMesh;

namespace {

// A cylinder of radius 1 from z = 0 to 1 and one of radius 1 - ring from z = 1 to 2, joined by a
// flat ring at z = 1, closed by fans at both ends: 32 segments around, one band per wall, as a CAD
// exporter writes it (the ring is 32 quads 0.2 long and `ring` wide, each two needles).
SurfaceMesh stepped_cylinder(double ring) {
  constexpr int kSegments = 32;
  constexpr double kPi = 3.14159265358979323846;
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  auto circle = [&](double r, double z) {
    const auto first = static_cast<std::uint32_t>(points.size());
    for (int i = 0; i < kSegments; ++i)
      points.push_back({r * std::cos(2 * kPi * i / kSegments), r * std::sin(2 * kPi * i / kSegments), z});
    return first;
  };
  const std::uint32_t base = circle(1, 0), step_out = circle(1, 1), step_in = circle(1 - ring, 1),
                      top = circle(1 - ring, 2);
  const auto bottom_centre = static_cast<std::uint32_t>(points.size());
  points.push_back({0, 0, 0});
  const auto top_centre = static_cast<std::uint32_t>(points.size());
  points.push_back({0, 0, 2});
  // The band from circle lo to circle hi, facing outwards (or up, for the ring).
  auto band = [&](std::uint32_t lo, std::uint32_t hi) {
    for (std::uint32_t i = 0; i < kSegments; ++i) {
      const std::uint32_t j = (i + 1) % kSegments;
      triangles.push_back({lo + i, lo + j, hi + j});
      triangles.push_back({lo + i, hi + j, hi + i});
    }
  };
  band(base, step_out);
  band(step_out, step_in);
  band(step_in, top);
  for (std::uint32_t i = 0; i < kSegments; ++i) {
    const std::uint32_t j = (i + 1) % kSegments;
    triangles.push_back({bottom_centre, base + j, base + i});
    triangles.push_back({top_centre, top + i, top + j});
  }
  return mesh::build_from_triangles(points, triangles);
}

// A unit square plate of 50 x 50 cells with a notch one cell deep and ten wide cut into its
// bottom border: the notch's corners turn by 90 degrees, 0.02 apart, in a flat plate whose sizing
// is the max length.
SurfaceMesh notched_plate() {
  constexpr std::uint32_t kCells = 50, kNotchFirst = 20, kNotchCells = 10;
  std::vector<std::array<double, 3>> points;
  for (std::uint32_t j = 0; j <= kCells; ++j)
    for (std::uint32_t i = 0; i <= kCells; ++i) points.push_back({double(i) / kCells, double(j) / kCells, 0});
  auto at = [&](std::uint32_t i, std::uint32_t j) { return j * (kCells + 1) + i; };
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (std::uint32_t j = 0; j < kCells; ++j)
    for (std::uint32_t i = 0; i < kCells; ++i) {
      if (j == 0 && i >= kNotchFirst && i < kNotchFirst + kNotchCells) continue;
      triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  // The notch's bottom corners are left without a triangle: build_from_triangles drops them.
  return mesh::build_from_triangles(points, triangles);
}

remesh::RemeshOptions adaptive_with_features(const SurfaceMesh& m, double epsilon_pct, double features) {
  remesh::RemeshOptions o = remesh::default_options_for(m);
  const double d = remesh::bounding_box_diagonal(m);
  o.epsilon = epsilon_pct * 0.01 * d;
  o.feature_angle_deg = features;
  return o;
}

}  // namespace

TEST(RemeshStrips, RingBetweenTwoFeatureLinesGetsTrianglesThatFitIt) {
  // Features on: both circles are feature lines, every vertex on them stays there, at every epsilon
  // (before the clamp: 12 degrees at epsilon 0.05 %, the input's own 5.9-degree needles at 0.5 and 2 %).
  const SurfaceMesh input = stepped_cylinder(0.02);
  for (const double epsilon_pct : {0.05, 0.5, 2.0}) {
    SCOPED_TRACE("epsilon " + std::to_string(epsilon_pct) + " %");
    SurfaceMesh m = input;
    const remesh::RemeshReport r = remesh::remesh(m, adaptive_with_features(input, epsilon_pct, 45));
    ASSERT_NO_THROW(m.validate());
    EXPECT_TRUE(r.warning.empty()) << r.warning;
    EXPECT_LE(double(m.n_vertices()), 2.0 * r.estimated_vertices + 1000);
    EXPECT_EQ(geometry::self_intersections(m, 100).pairs.size(), 0u);
    EXPECT_GE(geometry::quality_report(m).min_angle_deg, 20.0);
  }
}

TEST(RemeshStrips, RingTheToleranceMayCutAcrossIsNotRefined) {
  // Features off at epsilon 0.5 %: a chord across the ring stays within the tolerance, the mesh
  // need not follow both circles, and the ring keeps the sizing its curvature gives (845 vertices;
  // refined to its width regardless, 2,996).
  const SurfaceMesh input = stepped_cylinder(0.02);
  SurfaceMesh m = input;
  remesh::remesh(m, adaptive_with_features(input, 0.5, 0));
  EXPECT_LE(m.n_vertices(), 1200u);
  EXPECT_GE(geometry::quality_report(m).min_angle_deg, 20.0);
}

// Short border edges between corners (strips.cpp clamp_sizing_to_short_lines): the notch's sides
// are border edges 0.02 long between two corners, and the triangle on each had them as its base
// under sides as long as the plate's sizing (14.0 degrees at epsilon 0.5 % before the clamp).
TEST(RemeshStrips, ShortBorderEdgeBetweenCornersGetsTrianglesThatFitIt) {
  const SurfaceMesh input = notched_plate();
  for (const double epsilon_pct : {0.5, 2.0}) {
    SCOPED_TRACE("epsilon " + std::to_string(epsilon_pct) + " %");
    SurfaceMesh m = input;
    const remesh::RemeshReport r = remesh::remesh(m, adaptive_with_features(input, epsilon_pct, 0));
    ASSERT_NO_THROW(m.validate());
    EXPECT_TRUE(r.warning.empty()) << r.warning;
    EXPECT_GE(geometry::quality_report(m).min_angle_deg, 20.0);
    EXPECT_LE(m.n_vertices(), 400u);  // about 290 without the notch's refinement
  }
}
