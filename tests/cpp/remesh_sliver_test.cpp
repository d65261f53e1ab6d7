// Vertex placement for slivers (cpp/remesh/sliver.cpp): Remesher::polish on a plane. The
// dragon's necks, its reason, are tested in remesh_neck_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "mesh/primitives.h"
#include "remesh/remesher.h"

using namespace adasculpt;
using mesh::SurfaceMesh;
using mesh::Vertex;

namespace {

double min_angle_around(const SurfaceMesh& m, Vertex v) {
  double worst = 180;
  for (mesh::Face f : m.faces(v)) {
    Vertex c[3];
    m.face_vertices(f, c);
    for (int i = 0; i < 3; ++i) {
      const Vec3 a = m.position(c[(i + 1) % 3]) - m.position(c[i]), b = m.position(c[(i + 2) % 3]) - m.position(c[i]);
      worst = std::min(worst, std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)) * 180 / M_PI);
    }
  }
  return worst;
}

}  // namespace

// A vertex pushed almost onto its neighbour leaves slivers in its fan that polish() removes by
// moving it back to a good place on the reference (the plane), touching nothing else.
TEST(RemeshSliver, PolishMovesTheCornerOfASliver) {
  SurfaceMesh m = mesh::make_grid(12, 1.0);
  remesh::RemeshOptions o;
  o.adaptive = false;
  o.target_length = 1.0 / 12;
  remesh::Remesher remesher(m, o);
  remesher.iterate();
  Vertex centre;
  for (Vertex v : m.vertices())
    if (!m.is_boundary(v) && (!centre.is_valid() || glm::length(m.position(v)) < glm::length(m.position(centre))))
      centre = v;
  ASSERT_TRUE(centre.is_valid());
  const Vertex neighbour = *m.vertices(centre).begin();
  m.position(centre) += 0.85 * (m.position(neighbour) - m.position(centre));
  ASSERT_LT(min_angle_around(m, centre), 15.0);
  const size_t vertices = m.n_vertices();
  std::vector<Point> before(m.positions().begin(), m.positions().end());
  EXPECT_GE(remesher.polish(), 1u);
  EXPECT_GE(min_angle_around(m, centre), 25.0);
  EXPECT_EQ(m.n_vertices(), vertices);
  EXPECT_NEAR(m.position(centre).z, 0.0, 1e-12);
  // Only the corners of the slivers moved: the centre and its ring.
  size_t moved = 0;
  for (Vertex v : m.vertices()) moved += m.position(v) != before[v.idx];
  EXPECT_LE(moved, 1 + m.valence(centre));
}
