// Necks narrower than the sizing field (cpp/remesh/neck.cpp): a thin torus, whose tube is one
// long neck, and the dragon's thin fins (when the shared meshes are present).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/quality.h"
#include "geometry/topology.h"
#include "io/load_mesh.h"
#include "mesh/build_from_triangles.h"
#include "remesh/remesher.h"

using namespace adasculpt;
using mesh::SurfaceMesh;

namespace {

// A torus of major radius R around the z axis with a tube of radius r: `around` vertices per
// ring, `rings` rings, quads split along one diagonal.
SurfaceMesh make_torus(double R, double r, int around, int rings) {
  const double pi = 3.14159265358979323846;
  std::vector<std::array<double, 3>> pts;
  std::vector<std::array<std::uint32_t, 3>> tris;
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < around; ++i) {
      const double phi = 2 * pi * j / rings, theta = 2 * pi * i / around;
      pts.push_back({(R + r * std::cos(theta)) * std::cos(phi), (R + r * std::cos(theta)) * std::sin(phi),
                     r * std::sin(theta)});
    }
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>((j % rings) * around + (i % around)); };
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < around; ++i) {
      tris.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      tris.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return mesh::build_from_triangles(pts, tris);
}

}  // namespace

// The tube is 0.019 around and min_length 0.028: meshed with edges of min_length, its triangles
// were needles (mean smallest angle 13-16 degrees, every triangle under 30). Sized by the girth,
// it becomes rings of mostly well-shaped triangles (mean 46-47 degrees, 1-10 % under 30: a few
// strips of slivers along the tube remain).
TEST(RemeshNeck, ThinTorusTubeIsMeshedAcrossItsGirth) {
  SurfaceMesh m = make_torus(1.0, 0.003, 6, 400);
  const int genus = geometry::genus(m);
  ASSERT_EQ(genus, 1);
  remesh::RemeshOptions o = remesh::default_options_for(m);
  o.min_length = 0.01 * remesh::bounding_box_diagonal(m);
  ASSERT_GT(o.min_length, 2 * M_PI * 0.003);  // the whole tube is a neck
  remesh::remesh(m, o);
  ASSERT_NO_THROW(m.validate());
  EXPECT_EQ(geometry::genus(m), genus);
  EXPECT_EQ(geometry::components(m), 1);
  geometry::QualityReport q = geometry::quality_report(m);
  EXPECT_EQ(q.degenerate_faces, 0u);
  EXPECT_GE(q.mean_min_angle_deg, 40.0);
  EXPECT_LT(q.pct_min_angle_lt_30, 25.0);
  // Refined only as far as the girth asks: about three vertices per ring, rings about a third
  // of the girth apart (2 pi R / (2 pi r / 3) rings of 3 vertices: 3000).
  EXPECT_LT(q.vertices, 6000u);
}

// dragon.off has fins whose necks are narrower than min_length (one 0.0047 around, min_length
// 0.0052). Before the necks were sized by their girth: 1.8 degrees, ten triangles under 10.
TEST(RemeshNeck, DragonFinsLeaveNoSlivers) {
  const std::string path = std::string(ADASCULPT_SHARED_MESHES_DIR) + "/dragon.off";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not found";
  SurfaceMesh input = io::load_mesh(path);
  SurfaceMesh m = input;
  remesh::remesh(m, remesh::default_options_for(m));
  ASSERT_NO_THROW(m.validate());
  EXPECT_EQ(geometry::genus(m), geometry::genus(input));
  EXPECT_EQ(geometry::components(m), geometry::components(input));
  geometry::QualityReport q = geometry::quality_report(m);
  EXPECT_EQ(q.degenerate_faces, 0u);
  EXPECT_GE(q.min_angle_deg, 5.0);
  EXPECT_LE(q.pct_min_angle_lt_10 * q.faces / 100.0, 2.0);  // at most two triangles under 10 degrees
  EXPECT_LT(q.pct_min_angle_lt_30, 0.05);
}
