// The embedded-fan certificate (geometry/embedded_fan.h) lets the crossing guard pass over every
// pair of faces around a vertex: it must never say "embedded" for a fan two of whose triangles
// cross (checked exactly, on fans made to cross and on thousands of random ones), and must say it
// for the ordinary fans of a smooth surface, or it saves nothing.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "geometry/embedded_fan.h"
#include "geometry/self_intersections.h"
#include "geometry_test_util.h"
#include "mesh/build_from_triangles.h"

using namespace adasculpt;

namespace {

using test::kPi;

// Whether two triangles of the closed fan (centre, ring[i], ring[i + 1]) cross, by the exact
// pair test with the fan's connectivity (the centre is vertex id k, ring[i] is id i).
bool fan_crosses(const Point& centre, const std::vector<Point>& ring) {
  const size_t k = ring.size();
  std::vector<Point> points = ring;
  points.push_back(centre);
  const auto c = static_cast<std::uint32_t>(k);
  for (size_t i = 0; i < k; ++i) {
    const std::array<std::uint32_t, 3> t = {c, std::uint32_t(i), std::uint32_t((i + 1) % k)};
    if (geometry::collinear(points[t[0]], points[t[1]], points[t[2]])) return true;  // counts as "not clear"
    for (size_t j = i + 1; j < k; ++j) {
      const std::array<std::uint32_t, 3> u = {c, std::uint32_t(j), std::uint32_t((j + 1) % k)};
      if (geometry::collinear(points[u[0]], points[u[1]], points[u[2]])) return true;
      if (geometry::faces_intersect(points, t, u)) return true;
    }
  }
  return false;
}

// k ring points at the given angles (radians), radius 1, heights z.
std::vector<Point> ring_at(const std::vector<double>& angles, const std::vector<double>& z) {
  std::vector<Point> ring;
  for (size_t i = 0; i < angles.size(); ++i) ring.push_back({std::cos(angles[i]), std::sin(angles[i]), z[i]});
  return ring;
}

}  // namespace

TEST(EmbeddedFan, CertifiesFlatAndCurvedFans) {
  for (double height : {0.0, -0.4, 0.7}) {  // flat, a cap, a cone opening upwards
    std::vector<double> angles, z;
    for (int i = 0; i < 6; ++i) angles.push_back(i * kPi / 3), z.push_back(height);
    const std::vector<Point> ring = ring_at(angles, z);
    EXPECT_TRUE(geometry::star_surely_embedded(Point(0.0), ring.data(), ring.size())) << height;
    EXPECT_FALSE(fan_crosses(Point(0.0), ring));
  }
  // A saddle: heights alternating up and down.
  std::vector<double> angles, z;
  for (int i = 0; i < 8; ++i) angles.push_back(i * kPi / 4), z.push_back(i % 2 ? 0.5 : -0.5);
  const std::vector<Point> saddle = ring_at(angles, z);
  EXPECT_TRUE(geometry::star_surely_embedded(Point(0.0), saddle.data(), saddle.size()));
}

// A ring that goes around the centre twice: every triangle turns the same way, yet the fan
// overlaps itself, and with the heights rising along the ring its triangles cross.
TEST(EmbeddedFan, RefusesAFanThatWindsTwice) {
  std::vector<double> angles, z;
  for (int i = 0; i < 7; ++i) angles.push_back(i * 4 * kPi / 7), z.push_back(0.1 * std::sin(i * 4 * kPi / 7 + 0.3 * i));
  const std::vector<Point> ring = ring_at(angles, z);
  EXPECT_FALSE(geometry::star_surely_embedded(Point(0.0), ring.data(), ring.size()));
  // The same ring flattened: it still winds twice (overlapping, without a crossing pair in 3D
  // only by luck of the heights); the certificate must refuse it whatever the heights.
  const std::vector<Point> flat = ring_at(angles, std::vector<double>(7, 0.0));
  EXPECT_FALSE(geometry::star_surely_embedded(Point(0.0), flat.data(), flat.size()));
}

// A fan folded over: one ring vertex pulled across to the other side of the centre, so that its
// two triangles turn over and overlap their neighbours there (all in one plane).
TEST(EmbeddedFan, RefusesAFoldedFan) {
  std::vector<double> angles, z;
  for (int i = 0; i < 6; ++i) angles.push_back(i * kPi / 3), z.push_back(0.0);
  std::vector<Point> ring = ring_at(angles, z);
  ring[0] = Point(-1.5, 0.1, 0.0);
  ASSERT_TRUE(fan_crosses(Point(0.0), ring));
  EXPECT_FALSE(geometry::star_surely_embedded(Point(0.0), ring.data(), ring.size()));
}

// Random fans, from mild to wild: whenever the certificate says "embedded", no two triangles
// cross. Both answers must occur, and many of the refused fans must really cross, or the test
// would not be testing anything.
TEST(EmbeddedFan, NeverCertifiesAFanThatCrossesItself) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  size_t certified = 0, crossing = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const size_t k = 3 + trial % 9;
    const double jitter = (trial % 4) * 0.4;  // 0: regular, up to 1.2: anything goes
    const double height = (trial % 3) * 0.5;
    const double turns = trial % 5 == 4 ? 2.0 : 1.0;
    std::vector<Point> ring;
    for (size_t i = 0; i < k; ++i) {
      const double a = turns * 2 * kPi * (double(i) + 0.45 * jitter * unit(rng)) / double(k);
      const double r = 1.0 + 0.8 * jitter * unit(rng);
      ring.push_back({r * std::cos(a) + 0.5 * jitter * unit(rng), r * std::sin(a) + 0.5 * jitter * unit(rng),
                      height * unit(rng)});
    }
    const Point centre(0.3 * jitter * unit(rng), 0.3 * jitter * unit(rng), 0.3 * jitter * unit(rng));
    const bool crosses = fan_crosses(centre, ring);
    crossing += crosses;
    if (geometry::star_surely_embedded(centre, ring.data(), ring.size())) {
      ++certified;
      EXPECT_FALSE(crosses) << "trial " << trial;
    }
  }
  EXPECT_GT(certified, 5000u);
  EXPECT_GT(crossing, 1000u);
}

// The mesh version reads the ring in the order of the faces, whichever way the circulator turns,
// and leaves border vertices to the pair tests.
TEST(EmbeddedFan, ReadsAVertexFanOfAMesh) {
  std::vector<std::array<double, 3>> p = {{0, 0, 0}};
  for (int k = 0; k < 6; ++k) p.push_back({std::cos(k * kPi / 3), std::sin(k * kPi / 3), 0.1 * (k % 2)});
  p.push_back({0, 0, -1});  // closes the fan into a double cone below
  std::vector<std::array<std::uint32_t, 3>> t;
  for (std::uint32_t k = 0; k < 6; ++k) t.push_back({0, 1 + k, 1 + (k + 1) % 6});
  for (std::uint32_t k = 0; k < 6; ++k) t.push_back({7, 1 + (k + 1) % 6, 1 + k});
  const mesh::SurfaceMesh closed = mesh::build_from_triangles(p, t);
  EXPECT_TRUE(geometry::fan_surely_embedded(closed, mesh::Vertex(0)));
  EXPECT_TRUE(geometry::fan_surely_embedded(closed, mesh::Vertex(7)));
  t.resize(6);  // the top fan alone: its ring vertices are on the border
  p.pop_back();
  const mesh::SurfaceMesh open = mesh::build_from_triangles(p, t);
  EXPECT_TRUE(geometry::fan_surely_embedded(open, mesh::Vertex(0)));
  EXPECT_FALSE(geometry::fan_surely_embedded(open, mesh::Vertex(1)));
}
