// Geometric safety of the remeshing operations (issue 17 item 2): parts thinner than the target
// length keep their two sides apart instead of crumpling.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "geometry/self_intersections.h"
#include "geometry/topology.h"
#include "mesh/build_from_triangles.h"
#include "remesh/remesher.h"

using namespace adasculpt;
using mesh::SurfaceMesh;

namespace {

// The sweep's gen/thin_plate: a 1 x 1 plate `thickness` thick, 8 vertices and 12 triangles
// (the sides are 1 x thickness needles).
SurfaceMesh thin_plate(double thickness) {
  std::vector<std::array<double, 3>> points;
  for (double x : {0.0, 1.0})
    for (double y : {0.0, 1.0})
      for (double z : {0.0, thickness}) points.push_back({x, y, z});
  const std::vector<std::array<std::uint32_t, 3>> triangles = {
      {0, 2, 6}, {0, 6, 4}, {1, 5, 7}, {1, 7, 3}, {0, 1, 3}, {0, 3, 2},
      {4, 6, 7}, {4, 7, 5}, {0, 4, 5}, {0, 5, 1}, {2, 3, 7}, {2, 7, 6},
  };
  return mesh::build_from_triangles(points, triangles);
}

struct PlateCase {
  bool adaptive;
  double length_or_epsilon;  // of the diagonal
};

}  // namespace

// Before the projection looked only at the reference triangles facing a vertex's own way, a
// vertex of the bottom whose walk started on the top went to the top with its fan: 490 (epsilon
// 0.5 %) to 13,725 (length 2 %) crossing pairs.
TEST(RemeshSafety, ThinPlateStaysCrossingFree) {
  for (const PlateCase c : {PlateCase{false, 0.02}, PlateCase{false, 0.08}, PlateCase{true, 0.005}}) {
    SurfaceMesh m = thin_plate(0.002);
    remesh::RemeshOptions o = remesh::default_options_for(m);
    const double diagonal = remesh::bounding_box_diagonal(m);
    o.adaptive = c.adaptive;
    if (c.adaptive)
      o.epsilon = c.length_or_epsilon * diagonal;
    else
      o.target_length = c.length_or_epsilon * diagonal;
    remesh::remesh(m, o);
    SCOPED_TRACE(testing::Message() << (c.adaptive ? "epsilon " : "length ") << c.length_or_epsilon);
    EXPECT_GT(m.n_vertices(), 8u);
    EXPECT_EQ(geometry::self_intersections(m, 1000).pairs.size(), 0u);
    EXPECT_EQ(geometry::genus(m), 0);
  }
}
