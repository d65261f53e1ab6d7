// The judge's split of a remesh's self-intersections into those that re-sample a crossing the
// input already had and those the remesher made (geometry/inherited_crossings.h).
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "geometry/inherited_crossings.h"
#include "geometry/self_intersections.h"
#include "mesh/build_from_triangles.h"

using namespace adasculpt;

namespace {

// A soup of flat square sheets, each an n x n grid of quads (two triangles each).
struct Soup {
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;

  // The sheet spans origin + s u + t v for s, t in [0, 1].
  void sheet(std::array<double, 3> origin, std::array<double, 3> u, std::array<double, 3> v, int n) {
    const auto base = static_cast<std::uint32_t>(points.size());
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const double s = double(i) / n, t = double(j) / n;
        points.push_back({origin[0] + s * u[0] + t * v[0], origin[1] + s * u[1] + t * v[1],
                          origin[2] + s * u[2] + t * v[2]});
      }
    auto at = [&](int i, int j) { return base + static_cast<std::uint32_t>(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      }
  }
  mesh::SurfaceMesh build() const { return mesh::build_from_triangles(points, triangles); }
};

// Two sheets through each other along the x axis, and two sheets at x = 10 a given gap apart
// (a gap below zero: the second passes through the first).
Soup scene(int n, double gap) {
  Soup soup;
  soup.sheet({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, n);         // z = 0
  soup.sheet({-1, 0.1, -1}, {2, 0, 0}, {0, 0, 2}, n);       // y = 0.1, through the first
  soup.sheet({10, -1, 0}, {2, 0, 0}, {0, 2, 0}, n);         // z = 0, far away
  soup.sheet({10, 0.1, gap}, {2, 0, 0}, {0, 0, 2}, n);      // above it (gap > 0) or through it
  return soup;
}

size_t not_inherited(const mesh::SurfaceMesh& out, const mesh::SurfaceMesh& in, double margin) {
  const auto out_pairs = geometry::self_intersections(out);
  const auto in_pairs = geometry::self_intersections(in);
  return geometry::count_crossings_not_inherited(out, out_pairs, in, in_pairs, margin);
}

}  // namespace

TEST(InheritedCrossings, ARefinedCrossingOfTheInputIsNotNew) {
  const mesh::SurfaceMesh input = scene(1, 0.5).build();
  const mesh::SurfaceMesh refined = scene(4, 0.5).build();
  const auto in_pairs = geometry::self_intersections(input);
  const auto out_pairs = geometry::self_intersections(refined);
  ASSERT_GT(in_pairs.pairs.size(), 0u);
  ASSERT_GT(out_pairs.pairs.size(), in_pairs.pairs.size());  // "output minus input" would call these new
  EXPECT_EQ(geometry::count_crossings_not_inherited(refined, out_pairs, input, in_pairs, 0.0), 0u);
}

TEST(InheritedCrossings, ACrossingWhereTheInputHadNoneIsNew) {
  const mesh::SurfaceMesh input = scene(1, 0.5).build();
  const mesh::SurfaceMesh crossing_far = scene(4, -1.0).build();  // the far pair now passes through
  const auto far_pairs = geometry::self_intersections(scene(4, -1.0).build()).pairs.size() -
                         geometry::self_intersections(scene(4, 0.5).build()).pairs.size();
  ASSERT_GT(far_pairs, 0u);
  EXPECT_EQ(not_inherited(crossing_far, input, 0.0), far_pairs);
  // A margin smaller than the distance to the input's crossing does not excuse them either.
  EXPECT_EQ(not_inherited(crossing_far, input, 1.0), far_pairs);
}

TEST(InheritedCrossings, AnInputWithoutCrossingsExcusesNothing) {
  Soup apart;
  apart.sheet({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 1);
  apart.sheet({-1, 0.1, 0.5}, {2, 0, 0}, {0, 0, 2}, 1);
  const mesh::SurfaceMesh crossing = scene(2, 0.5).build();
  const size_t all = geometry::self_intersections(crossing).pairs.size();
  ASSERT_GT(all, 0u);
  EXPECT_EQ(not_inherited(crossing, apart.build(), 0.5), all);
}
