// Where the crossing guard (crossing_guard.h) let crossings through: its bounded work, and the
// crossings it excuses as the input's.
//
// A pass that spends the work of the guard's grid must not go on unchecked. Coarsening a finely meshed input (cylinder_locally_refined at
// uniform 2 %, turbine and man at uniform 8 %) spent it within the first collapse pass, and the
// collapses after that made the sweep's new crossing pairs. The grid is renewed instead, and once
// the renewals are spent too every operation is refused until the next start().
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "geometry/self_intersections.h"
#include "geometry_test_util.h"
#include "mesh/build_from_triangles.h"
#include "remesh/crossing_guard.h"

using namespace adasculpt;
using mesh::SurfaceMesh;
using mesh::Vertex;

namespace {

using test::kPi;

// A hexagonal fan around vertex 0 with ring vertex 1 lowered to z = -0.6, and a small separate
// triangle (vertices 7-9) at z = -0.15 under the far half of the fan: collapsing 0 into 1 tilts
// the fan down through that triangle (as in remesh_crossing_guard_test's dented fan).
SurfaceMesh fan_over_a_sheet() {
  std::vector<std::array<double, 3>> p = {{0, 0, 0}};
  for (int k = 0; k < 6; ++k) p.push_back({std::cos(k * kPi / 3), std::sin(k * kPi / 3), k == 0 ? -0.6 : 0.0});
  std::vector<std::array<std::uint32_t, 3>> t;
  for (std::uint32_t k = 0; k < 6; ++k) t.push_back({0, 1 + k, 1 + (k + 1) % 6});
  p.push_back({-0.8, 0, -0.15});
  p.push_back({-0.3, -0.1, -0.15});
  p.push_back({-0.3, 0.1, -0.15});
  t.push_back({7, 8, 9});
  return mesh::build_from_triangles(p, t);
}

// Harmless tests (the sheet's own fan crosses nothing) until the guard refuses one: every test
// spends work. Returns how many passed (the cap when none was refused).
size_t tests_until_refused(remesh::CrossingGuard& guard, const SurfaceMesh& m, size_t cap) {
  for (size_t n = 0; n < cap; ++n)
    if (guard.fan_crosses(m, Vertex(7))) return n;
  return cap;
}

constexpr size_t kCap = 50000000;

}  // namespace

TEST(CrossingGuardBudget, KeepsCheckingAfterTheFirstGridsWorkIsSpent) {
  const SurfaceMesh m = fan_over_a_sheet();
  ASSERT_EQ(geometry::self_intersections(m).pairs.size(), 0u);
  const mesh::Halfedge collapse = m.find_halfedge(Vertex(0), Vertex(1));
  remesh::CrossingGuard guard;
  guard.start(m);
  const size_t all_work = tests_until_refused(guard, m, kCap);
  ASSERT_LT(all_work, kCap) << "the guard never refuses once its work is spent";
  // Halfway through the renewals the first grid's work is long spent: the guard still tells the
  // crossing collapse from the harmless test.
  guard.start(m);
  ASSERT_EQ(tests_until_refused(guard, m, all_work / 2), all_work / 2);
  EXPECT_TRUE(guard.active());
  EXPECT_TRUE(guard.collapse_crosses(m, collapse, m.position(Vertex(1)), false));
  EXPECT_FALSE(guard.fan_crosses(m, Vertex(7)));
}

TEST(CrossingGuardBudget, RefusesEveryOperationOnceTheRenewalsAreSpentUntilTheNextStart) {
  const SurfaceMesh m = fan_over_a_sheet();
  remesh::CrossingGuard guard;
  guard.start(m);
  ASSERT_LT(tests_until_refused(guard, m, kCap), kCap);
  // A collapse that crosses nothing (the centre into ring vertex 3, away from the sheet) is
  // refused too: unchecked, it might cross.
  const mesh::Halfedge harmless = m.find_halfedge(Vertex(0), Vertex(3));
  EXPECT_TRUE(guard.collapse_crosses(m, harmless, m.position(Vertex(3)), false));
  guard.start(m);
  EXPECT_FALSE(guard.collapse_crosses(m, harmless, m.position(Vertex(3)), false));
  EXPECT_FALSE(guard.fan_crosses(m, Vertex(7)));
}

// A collapse whose replaced faces cross the sheet already keeps that crossing (excused), but its
// new triangles meet the sheet's box beyond where the old faces did: the input's clean-up
// refuses it (contain_inherited_crossings), the passes after it do not.
TEST(CrossingGuardInherited, TheCleanUpKeepsAnInputCrossingWhereItWas) {
  SurfaceMesh m = fan_over_a_sheet();
  // The sheet now pierces the flat far half of the fan (z = 0) at x = -0.7, from z = 0.1 at its
  // tip down to -0.4; the collapse's new triangles slope down to z = -0.6 and meet it below 0.
  m.position(Vertex(7)).z = 0.1;
  m.position(Vertex(8)).z = -0.4;
  m.position(Vertex(9)).z = -0.4;
  ASSERT_GT(geometry::self_intersections(m).pairs.size(), 0u);
  const mesh::Halfedge collapse = m.find_halfedge(Vertex(0), Vertex(1));
  remesh::CrossingGuard guard;
  guard.start(m);
  EXPECT_FALSE(guard.collapse_crosses(m, collapse, m.position(Vertex(1)), false));
  guard.contain_inherited_crossings(true);
  EXPECT_TRUE(guard.collapse_crosses(m, collapse, m.position(Vertex(1)), false));
  guard.start(m);  // back to excusing it
  EXPECT_FALSE(guard.collapse_crosses(m, collapse, m.position(Vertex(1)), false));
  // The collapse really takes the crossing beyond the old faces: below the fan's plane.
  m.collapse(collapse);
  bool below = false;
  const geometry::SelfIntersectionReport crossings = geometry::self_intersections(m);
  for (const auto& pair : crossings.pairs)
    for (const std::uint32_t f : {pair.first, pair.second}) {
      Vertex corners[3];
      m.face_vertices(mesh::Face(f), corners);
      for (const Vertex v : corners) below = below || (v != Vertex(7) && m.position(v).z < 0);
    }
  EXPECT_TRUE(below);
}
