// Mirror symmetry detection (geometry/mirror_symmetry.h), which decides whether a symmetric brush
// stroke can keep the mesh exactly symmetric.
#include <gtest/gtest.h>

#include "geometry/mirror_symmetry.h"
#include "mesh/primitives.h"

namespace adasculpt {
namespace {

using mesh::Vertex;

TEST(GeometryMirror, IcosphereIsSymmetricAcrossEveryCoordinatePlane) {
  const mesh::SurfaceMesh m = mesh::make_icosphere(3);
  for (int axis = 0; axis < 3; ++axis) {
    const std::vector<Vertex> image = geometry::find_mirror_map(m, axis);
    ASSERT_EQ(image.size(), m.vertices_size()) << "axis " << axis;
    size_t on_plane = 0;
    for (Vertex v : m.vertices()) {
      const Vertex w = image[v.idx];
      ASSERT_TRUE(w.is_valid());
      EXPECT_EQ(image[w.idx], v) << "the map is an involution";
      Point p = m.position(v);
      p[axis] = -p[axis];
      EXPECT_EQ(m.position(w), p);
      on_plane += w == v;
    }
    EXPECT_GT(on_plane, 0u) << "vertices on the plane are their own image";
    EXPECT_TRUE(geometry::is_mirror_symmetric(m, axis));
  }
}

TEST(GeometryMirror, AnyMovedVertexBreaksTheSymmetry) {
  mesh::SurfaceMesh m = mesh::make_icosphere(2);
  for (Vertex v : m.vertices())
    if (m.position(v).x > 0.1) {  // off the plane (on it, a vertex is its own image whatever its y)
      m.position(v).y += 1e-12;
      break;
    }
  EXPECT_TRUE(geometry::find_mirror_map(m, 0).empty());
  EXPECT_FALSE(geometry::is_mirror_symmetric(m, 0));
  mesh::SurfaceMesh shifted = mesh::make_icosphere(2);
  for (Vertex v : shifted.vertices()) shifted.position(v).x += 0.5;  // symmetric, but not about x = 0
  EXPECT_FALSE(geometry::is_mirror_symmetric(shifted, 0));
}

TEST(GeometryMirror, SymmetricPointsWithAsymmetricTrianglesAreNotSymmetric) {
  mesh::SurfaceMesh m = mesh::make_icosphere(2);
  // Flip one edge off the plane x = 0: same points, triangles no longer mirror each other.
  for (mesh::Edge e : m.edges()) {
    const Point a = m.position(m.vertex(e, 0)), b = m.position(m.vertex(e, 1));
    if (a.x > 0.1 && b.x > 0.1 && m.is_flip_ok(e)) {
      m.flip(e);
      break;
    }
  }
  EXPECT_FALSE(geometry::find_mirror_map(m, 0).empty()) << "the points are still symmetric";
  EXPECT_FALSE(geometry::is_mirror_symmetric(m, 0));
  EXPECT_TRUE(geometry::is_mirror_symmetric(mesh::make_icosphere(2), 0));
}

}  // namespace
}  // namespace adasculpt
