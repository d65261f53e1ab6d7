// Loading soups whose faces disagree about which side is out (mesh/orient_faces.h): they are
// reversed into one orientation, outwards for a closed piece; one-sided surfaces are refused.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "io/load_mesh.h"
#include "mesh/build_from_triangles.h"
#include "mesh/primitives.h"
#include "mesh/surface_mesh.h"

using namespace adasculpt;
using namespace adasculpt::mesh;

namespace {

// Six times the volume, from the built mesh's faces (negative when they face inwards).
double volume6(const SurfaceMesh& m) {
  double sum = 0;
  for (Face f : m.faces()) {
    Vertex v[3];
    m.face_vertices(f, v);
    sum += glm::dot(m.position(v[0]), glm::cross(m.position(v[1]), m.position(v[2])));
  }
  return sum;
}

// Reverses each face with probability 1/2 (as CGAL's *-shuffled.off files are): returns how many.
size_t shuffle_orientation(std::vector<std::array<std::uint32_t, 3>>& t, unsigned seed) {
  std::mt19937 rng(seed);
  size_t n = 0;
  for (auto& f : t)
    if (rng() & 1u) std::swap(f[1], f[2]), ++n;
  return n;
}

// Whether every face of m runs its corners as in one of the given triangles, up to rotation.
bool all_faces_as_in(const SurfaceMesh& m, const std::vector<std::array<std::uint32_t, 3>>& expected) {
  auto canonical = [](std::array<std::uint32_t, 3> t) {
    while (t[0] > t[1] || t[0] > t[2]) t = {t[1], t[2], t[0]};
    return t;
  };
  std::vector<std::array<std::uint32_t, 3>> want;
  for (const auto& t : expected) want.push_back(canonical(t));
  std::sort(want.begin(), want.end());
  for (Face f : m.faces()) {
    Vertex v[3];
    m.face_vertices(f, v);
    if (!std::binary_search(want.begin(), want.end(), canonical({v[0].idx, v[1].idx, v[2].idx}))) return false;
  }
  return true;
}

}  // namespace

TEST(OrientFaces, ShuffledClosedSurfacesFaceOutwards) {
  const io::PolygonSoup sphere = io::soup_from_mesh(make_icosphere(3));
  const io::PolygonSoup box = io::soup_from_mesh(make_box(3, 4, 5));
  for (const io::PolygonSoup* soup : {&sphere, &box})
    for (unsigned seed = 1; seed <= 20; ++seed) {
      auto t = soup->triangles;
      const size_t shuffled = shuffle_orientation(t, seed);
      BuildReport report;
      const SurfaceMesh m = build_from_triangles(soup->points, t, &report);
      EXPECT_EQ(report.reoriented_faces, shuffled) << "seed " << seed;
      ASSERT_EQ(report.warnings.size(), 1u);
      EXPECT_NE(report.warnings[0].find("reversed " + std::to_string(shuffled) + " face(s)"), std::string::npos);
      EXPECT_GT(volume6(m), 0) << "seed " << seed;
      // The generator's vertex numbering is kept (every vertex is used), so the faces must be
      // exactly the unshuffled ones.
      EXPECT_TRUE(all_faces_as_in(m, soup->triangles)) << "seed " << seed;
    }
}

TEST(OrientFaces, ClosedSurfaceTurnedInsideOutByShufflingFacesOutwards) {
  // Every face but one reversed: the majority faces inwards, the volume still decides.
  const io::PolygonSoup sphere = io::soup_from_mesh(make_icosphere(2));
  auto t = sphere.triangles;
  for (size_t i = 1; i < t.size(); ++i) std::swap(t[i][1], t[i][2]);
  BuildReport report;
  const SurfaceMesh m = build_from_triangles(sphere.points, t, &report);
  EXPECT_EQ(report.reoriented_faces, t.size() - 1);
  EXPECT_GT(volume6(m), 0);
}

TEST(OrientFaces, ConsistentInsideOutFileIsLeftAsWritten) {
  // Consistent but facing inwards: the file's choice, not an error to repair.
  const io::PolygonSoup sphere = io::soup_from_mesh(make_icosphere(2));
  auto t = sphere.triangles;
  for (auto& f : t) std::swap(f[1], f[2]);
  BuildReport report;
  const SurfaceMesh m = build_from_triangles(sphere.points, t, &report);
  EXPECT_EQ(report.reoriented_faces, 0u);
  EXPECT_TRUE(report.warnings.empty());
  EXPECT_LT(volume6(m), 0);
}

TEST(OrientFaces, OpenSheetKeepsTheOrientationMostFacesHad) {
  const io::PolygonSoup grid = io::soup_from_mesh(make_grid(8));
  auto t = grid.triangles;
  // A few faces reversed: those are the ones repaired, whatever their number or place.
  for (size_t i = 0; i < t.size(); i += 7) std::swap(t[i][1], t[i][2]);
  BuildReport report;
  const SurfaceMesh m = build_from_triangles(grid.points, t, &report);
  EXPECT_EQ(report.reoriented_faces, (t.size() + 6) / 7);
  EXPECT_TRUE(all_faces_as_in(m, grid.triangles));
}

TEST(OrientFaces, EachPieceIsOrientedOnItsOwn) {
  // Two spheres side by side: one consistent and inside out (left so), one shuffled (outwards).
  const io::PolygonSoup sphere = io::soup_from_mesh(make_icosphere(2));
  std::vector<std::array<double, 3>> p = sphere.points;
  const auto base = static_cast<std::uint32_t>(p.size());
  for (auto q : sphere.points) p.push_back({q[0] + 3, q[1], q[2]});
  std::vector<std::array<std::uint32_t, 3>> t;
  for (auto f : sphere.triangles) t.push_back({f[0], f[2], f[1]});
  auto second = sphere.triangles;
  const size_t shuffled = shuffle_orientation(second, 7);
  for (auto f : second) t.push_back({f[0] + base, f[1] + base, f[2] + base});
  BuildReport report;
  const SurfaceMesh m = build_from_triangles(p, t, &report);
  EXPECT_EQ(report.reoriented_faces, shuffled);
  // The first sphere's volume is negative, the second's positive and equal in size: they cancel.
  EXPECT_NEAR(volume6(m), 0, 1e-9);
}

TEST(OrientFaces, MoebiusStripIsRefusedWithTheEdge) {
  // A strip of 12 quads around a circle, its far end joined to its start after half a turn.
  const int n = 12;
  std::vector<std::array<double, 3>> p;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n, twist = a / 2;
    for (int s : {-1, 1}) {
      const double r = 2 + 0.5 * s * std::cos(twist);
      p.push_back({r * std::cos(a), r * std::sin(a), 0.5 * s * std::sin(twist)});
    }
  }
  std::vector<std::array<std::uint32_t, 3>> t;
  for (int i = 0; i < n; ++i) {
    const std::uint32_t a0 = 2 * i, a1 = 2 * i + 1;
    // After the last quad the strip meets its start upside down: corner 0 joins corner 1.
    const bool last = i == n - 1;
    const std::uint32_t b0 = last ? 1 : 2 * (i + 1), b1 = last ? 0 : 2 * (i + 1) + 1;
    t.push_back({a0, b0, a1});
    t.push_back({a1, b0, b1});
  }
  try {
    build_from_triangles(p, t);
    FAIL() << "expected a TopologyError";
  } catch (const TopologyError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("inconsistent face orientation at the edge between vertices"), std::string::npos) << what;
    EXPECT_NE(what.find("one-sided"), std::string::npos) << what;
  }
}
