// Zero-area input triangles (issue 17): the remesher repairs them before it refines, so a flat
// input with collinear or coincident corners remeshes as its clean twin does, into a bounded
// number of well-shaped triangles, instead of splitting its zero-area triangles into more.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "geometry/quality.h"
#include "geometry/topology.h"
#include "geometry/triangle.h"
#include "mesh/build_from_triangles.h"
#include "remesh/remesher.h"

using namespace adasculpt;
using mesh::SurfaceMesh;

namespace {

using Points = std::vector<std::array<double, 3>>;
using Triangles = std::vector<std::array<std::uint32_t, 3>>;

// CGAL's degtri_sliding.off: two flat triangles (below and above y = 0) joined along y = 0 by a
// strip of four triangles whose corners are all on that line.
const Points kSlidingPoints = {{4, -2, 0}, {6, 0, 0}, {4, 0, 0}, {2, 0, 0}, {1, 0, 0}, {3, 0, 0}, {5, 0, 0}, {3, 2, 0}};
SurfaceMesh sliding_strip() {
  return mesh::build_from_triangles(kSlidingPoints,
                                    Triangles{{0, 1, 2}, {0, 2, 3}, {3, 2, 4}, {2, 1, 6}, {2, 6, 4}, {4, 6, 5}, {5, 6, 7}, {4, 5, 7}});
}
// The same polygon and points triangulated without a zero-area triangle.
SurfaceMesh sliding_clean() {
  return mesh::build_from_triangles(kSlidingPoints,
                                    Triangles{{0, 1, 6}, {0, 6, 2}, {2, 6, 7}, {2, 7, 5}, {0, 2, 5}, {0, 5, 3}, {3, 5, 7}, {4, 3, 7}});
}

// A unit square fanned around its centre, where the centre is two vertices at the same place
// joined by an edge of length zero: the two triangles on that edge are needles of zero area.
SurfaceMesh square_with_zero_length_edge() {
  const Points points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0}, {0.5, 0.5, 0}};
  return mesh::build_from_triangles(points, Triangles{{0, 1, 4}, {1, 2, 5}, {2, 3, 5}, {3, 0, 4}, {1, 5, 4}, {3, 4, 5}});
}

// A flat cap whose long side is on the border and ends at a vertex with no other triangle (the
// border folds back on itself there: the apex of a cone cut open along a line looks like this
// when the cut's two sides meet), beside one triangle with area: (0,0)-(1,0)-(2,0) and
// (2,0)-(1,0)-(1.5,1). No flip can remove the cap (its long side is the border).
SurfaceMesh cap_on_a_border_fold() {
  const Points points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {1.5, 1, 0}};
  return mesh::build_from_triangles(points, Triangles{{0, 1, 2}, {2, 1, 3}});
}

// A roof (two halves meeting at 90 degrees along the x axis) whose ridge is two feature lines
// nearly on one line: the left half ends at the path (0,0,0), (1,0,0), (3,0,0), (4,0,0), the right
// half at (0,0,0), (2,d,0), (4,0,0), and between them a strip of three triangles of about d / 1 rad
// (d of 1e-7: 6e-6 degrees). Remeshed with features at 30 degrees, the strip's edges are feature
// lines and the remesher lays the two lines onto one. This is what --features 45 made of an input
// flap folded back onto its neighbour (cgal/pig.off at epsilon 1 %: three triangles of 0.00 degrees
// between two corners).
SurfaceMesh roof_with_a_doubled_ridge(double d) {
  const Points points = {{0, 0, 0},  {1, 0, 0},  {2, d, 0},  {3, 0, 0}, {4, 0, 0}, {0, -1, -1},
                         {1, -1, -1}, {3, -1, -1}, {4, -1, -1}, {0, 1, -1}, {2, 1, -1}, {4, 1, -1}};
  return mesh::build_from_triangles(points, Triangles{// left half, on the path 0 1 3 4
                                                      {5, 6, 1}, {5, 1, 0}, {6, 7, 3}, {6, 3, 1}, {7, 8, 4}, {7, 4, 3},
                                                      // right half, on the path 0 2 4
                                                      {0, 2, 10}, {0, 10, 9}, {2, 4, 11}, {2, 11, 10},
                                                      // the strip between the two paths
                                                      {0, 1, 2}, {1, 3, 2}, {3, 4, 2}});
}

size_t zero_area_faces(const SurfaceMesh& m) {
  size_t n = 0;
  for (mesh::Face f : m.faces()) {
    mesh::Vertex v[3];
    m.face_vertices(f, v);
    n += geometry::is_degenerate_triangle(m.position(v[0]), m.position(v[1]), m.position(v[2]));
  }
  return n;
}

remesh::RemeshOptions uniform(const SurfaceMesh& m, double length_pct) {
  remesh::RemeshOptions o = remesh::default_options_for(m);
  o.adaptive = false;
  o.target_length = length_pct * 0.01 * remesh::bounding_box_diagonal(m);
  return o;
}

}  // namespace

TEST(RemeshDegenerate, TheInputsHaveZeroAreaTriangles) {  // what the tests below start from
  EXPECT_EQ(zero_area_faces(sliding_strip()), 4u);
  EXPECT_EQ(zero_area_faces(sliding_clean()), 0u);
  EXPECT_EQ(zero_area_faces(square_with_zero_length_edge()), 2u);
  EXPECT_EQ(zero_area_faces(cap_on_a_border_fold()), 1u);
}

// Before: 18,444 vertices with 13,261 zero-area triangles at length 0.5 % (the strip's splits put
// every new vertex on its line and the projection pulled the vertices beside it onto the line), and
// at epsilon 0.01 % 56 s and 2.1 GB without an end (the zero-area triangles' curvature).
TEST(RemeshDegenerate, CollinearStripRemeshesAsItsCleanTwin) {
  for (const double length_pct : {2.0, 0.5}) {
    SCOPED_TRACE(testing::Message() << "length " << length_pct << " %");
    SurfaceMesh strip = sliding_strip(), clean = sliding_clean();
    const remesh::RemeshReport r = remesh::remesh(strip, uniform(strip, length_pct));
    remesh::remesh(clean, uniform(clean, length_pct));
    ASSERT_NO_THROW(strip.validate());
    EXPECT_TRUE(r.warning.empty()) << r.warning;
    EXPECT_EQ(zero_area_faces(strip), 0u);
    // The repairs leave the surface as it was: the same remesh as the clean triangulation's.
    EXPECT_EQ(strip.n_vertices(), clean.n_vertices());
    const geometry::QualityReport q = geometry::quality_report(strip);
    EXPECT_GE(q.min_angle_deg, 30.0);
    EXPECT_NEAR(q.area, geometry::quality_report(clean).area, 1e-9);
    EXPECT_LT(double(strip.n_vertices()), 2.0 * r.estimated_vertices);
  }
  // Adaptive at a tolerance far finer than the flat input needs: the flat strip asks for nothing.
  SurfaceMesh strip = sliding_strip();
  remesh::RemeshOptions o = remesh::default_options_for(strip);
  o.epsilon = 1e-4 * remesh::bounding_box_diagonal(strip);
  o.min_length = 2e-4 * remesh::bounding_box_diagonal(strip);
  const remesh::RemeshReport r = remesh::remesh(strip, o);
  EXPECT_LT(r.estimated_vertices, 200.0);  // area 8 at the 5 % max length: about 90
  EXPECT_LT(strip.n_vertices(), 300u);
  EXPECT_EQ(zero_area_faces(strip), 0u);
  EXPECT_GE(geometry::quality_report(strip).min_angle_deg, 30.0);
}

TEST(RemeshDegenerate, ZeroLengthEdgeCollapses) {
  SurfaceMesh m = square_with_zero_length_edge();
  const remesh::RemeshReport r = remesh::remesh(m, uniform(m, 10.0));
  ASSERT_NO_THROW(m.validate());
  EXPECT_TRUE(r.warning.empty()) << r.warning;
  EXPECT_EQ(zero_area_faces(m), 0u);
  EXPECT_EQ(geometry::genus(m), 0);
  const geometry::QualityReport q = geometry::quality_report(m);
  EXPECT_NEAR(q.area, 1.0, 1e-9);
  EXPECT_GE(q.min_angle_deg, 30.0);
  EXPECT_LT(m.n_vertices(), 300u);  // 1 / (0.141^2 sqrt(3) / 2) is about 60
}

// The polygon has two 45-degree border corners. Border vertices slide along the border, and the
// collapses of the corner vertices along it cut both corners off: Hausdorff 6 % of the diagonal at
// epsilon 2 % and 2.09 % at length 2 %. A collapse along a feature line or the border must keep
// the line within the tolerance of the vertex it removes.
TEST(RemeshDegenerate, BorderCornersStayWithinTheTolerance) {
  const SurfaceMesh input = sliding_clean();
  SurfaceMesh adaptive = input, fixed_length = input;
  remesh::RemeshOptions o = remesh::default_options_for(input);
  o.epsilon = 0.02 * remesh::bounding_box_diagonal(input);
  remesh::remesh(adaptive, o);
  EXPECT_LE(geometry::distance_between(adaptive, input, 20000).hausdorff_rel, 0.04);  // 2 epsilon
  remesh::remesh(fixed_length, uniform(input, 2.0));
  EXPECT_LE(geometry::distance_between(fixed_length, input, 20000).hausdorff_rel, 0.02);  // the length
  EXPECT_GE(geometry::quality_report(fixed_length).min_angle_deg, 30.0);
}

// Before: the split passes cut the cap's border edge again and again, each cut leaving more flat
// triangles on the line (1,187 vertices at the default epsilon, mean min angle 1.6 degrees). The
// fold's vertex carries no surface but the cap's, and collapses onto the cap's corner.
TEST(RemeshDegenerate, CapOnABorderFoldIsRemoved) {
  const SurfaceMesh input = cap_on_a_border_fold();
  for (const bool adaptive : {true, false}) {
    SCOPED_TRACE(adaptive ? "adaptive, default epsilon" : "uniform length 10 %");
    SurfaceMesh m = input;
    const remesh::RemeshReport r = remesh::remesh(m, adaptive ? remesh::default_options_for(m) : uniform(m, 10.0));
    ASSERT_NO_THROW(m.validate());
    EXPECT_TRUE(r.warning.empty()) << r.warning;
    EXPECT_EQ(zero_area_faces(m), 0u);
    const geometry::QualityReport q = geometry::quality_report(m);
    EXPECT_NEAR(q.area, 0.5, 1e-9);  // the triangle with area, all of it
    EXPECT_GE(q.min_angle_deg, 25.0);
    EXPECT_LT(m.n_vertices(), 200u);
  }
}

// Before: the remesh ended with triangles of 0.00 degrees where the two lines met, between
// corners and feature lines that every repair keeps apart and in place. Now the last repair of
// polish() collapses their edges across those rules where the surface stays within the tolerance.
TEST(RemeshDegenerate, FlatTrianglesBetweenTwoFeatureLinesAreRemoved) {
  for (const double d : {1e-7, -1e-7}) {
    SCOPED_TRACE(testing::Message() << "ridge offset " << d);
    const SurfaceMesh input = roof_with_a_doubled_ridge(d);
    SurfaceMesh m = input;
    remesh::RemeshOptions o = remesh::default_options_for(m);
    o.feature_angle_deg = 30;
    const remesh::RemeshReport r = remesh::remesh(m, o);
    ASSERT_NO_THROW(m.validate());
    EXPECT_TRUE(r.warning.empty()) << r.warning;
    EXPECT_EQ(zero_area_faces(m), 0u);
    EXPECT_GE(geometry::quality_report(m).min_angle_deg, 1.0);  // polish()'s threshold
    EXPECT_EQ(geometry::genus(m), 0);
    EXPECT_LE(geometry::distance_between(m, input, 20000).hausdorff_rel,
              2 * o.epsilon / remesh::bounding_box_diagonal(input));
  }
}
