// Issue 17's Hausdorff target at the sharp edges of coarse polyhedra (remesh/fidelity.cpp): with
// features off, a flat-faced input has no curvature to size its edges by, and the remeshed surface
// must still stay within 2 epsilon of it (measured by the sampled distance stats --reference
// uses); coarser settings still give fewer vertices.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstddef>
#include <filesystem>
#include <string>
#include <initializer_list>
#include <vector>

#include "geometry/quality.h"
#include "geometry_test_util.h"
#include "io/load_mesh.h"
#include "geometry/self_intersections.h"
#include "mesh/build_from_triangles.h"
#include "mesh/primitives.h"
#include "remesh/remesher.h"
#include "remesh_test_util.h"
#include "test_build.h"

using namespace adasculpt;
using mesh::SurfaceMesh;

namespace {

// A square pyramid twice as long as its base is wide: 5 vertices, 6 triangles, edges turning by
// 63 to 117 degrees and a tip sharper than a cube's corner.
SurfaceMesh long_pyramid() {
  const std::vector<std::array<double, 3>> points = {
      {-1, -0.5, -0.5}, {-1, -0.5, 0.5}, {-1, 0.5, 0.5}, {-1, 0.5, -0.5}, {1, 0, 0}};
  const std::vector<std::array<std::uint32_t, 3>> triangles = {{1, 0, 4}, {2, 1, 4}, {3, 2, 4},
                                                               {0, 3, 4}, {0, 1, 2}, {0, 2, 3}};
  return mesh::build_from_triangles(points, triangles);
}

struct Remeshed {
  SurfaceMesh mesh;
  double hausdorff_rel;  // symmetric, over the input's diagonal
};

// Adaptive remesh with features off; epsilon and min length as fractions of the diagonal.
Remeshed remeshed(const SurfaceMesh& input, double epsilon, double min_length) {
  Remeshed r{input, 0};
  test::remesh_relative(r.mesh, epsilon, min_length);
  r.hausdorff_rel = geometry::distance_between(r.mesh, input, 20000).hausdorff_rel;
  return r;
}

void expect_within_twice_epsilon(const SurfaceMesh& input, std::initializer_list<double> epsilons) {
  for (const double epsilon : epsilons) {
    SCOPED_TRACE(testing::Message() << "epsilon " << epsilon);
    const Remeshed r = remeshed(input, epsilon, 0.0002);
    EXPECT_LE(r.hausdorff_rel, 2 * epsilon);
    EXPECT_NO_THROW(r.mesh.validate());
    EXPECT_EQ(geometry::self_intersections(r.mesh, 1000).pairs.size(), 0u);
  }
}

// The sweep's fine settings: epsilon 0.01 % and 0.05 % with min length 0.02 %, features off.
// Before the fidelity check: 0.89 % and 0.66 % of the diagonal (the long edges cut by edges of
// the max length).
TEST(RemeshFidelity, CoarsePyramidStaysWithinTwiceEpsilon) {
  expect_within_twice_epsilon(long_pyramid(), {0.0001, 0.0005});
}

// Before: 0.55 % of the diagonal at epsilon 0.01 % (edges turning by 42 degrees, below the crease
// test of the guarded projection, slid off by the relaxation). At 0.05 % the icosahedron's own
// corners, blunter than a cube's and so not kept as tips (tips.cpp), are cut by 1.03 x 2 epsilon.
TEST(RemeshFidelity, IcosahedronStaysWithinTwiceEpsilon) {
  expect_within_twice_epsilon(mesh::make_icosphere(0), {0.0001});
}

// The corner of the unit cube cut off as a tetrahedron: edges turning by 90 and 125 degrees. The
// distance runs both ways: the limits kept every edge within 1.24 epsilon of the faces at epsilon
// 1 %, but the edges cut the tetrahedron's own edges 2.29 epsilon deep (a crease lies farther from
// a chord than the chord from the two faces). Now the limits shrink over a crease: 1.58 epsilon.
TEST(RemeshFidelity, TetrahedronEdgesStayWithinTwiceEpsilonOfTheRemeshedSurface) {
  const SurfaceMesh tetrahedron = mesh::build_from_triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                                                             {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}});
  expect_within_twice_epsilon(tetrahedron, {0.01, 0.005});
}

// A unit box with one vertical edge cut off by a narrow chamfer (c wide): two creases of 45
// degrees, a strip of two long triangles between them. The vertex curvature spreads the creases'
// turn over large fans, so the sizing asks for edges many times the chamfer's width; the edges
// across the strip keep their midpoints near the faces, and the strip was cut off: 1.75 % of the
// diagonal at epsilon 0.05 % (c = 0.01), 0.59 % at 0.01 % (c = 0.03). Coverage now samples the
// creases (coverage.cpp): 0.09 % and 0.018 %.
SurfaceMesh chamfered_box(double c) {
  const std::vector<std::array<double, 2>> outline = {{0, 0}, {1, 0}, {1, 1 - c}, {1 - c, 1}, {0, 1}};
  std::vector<std::array<double, 3>> points;
  for (const double z : {0.0, 1.0})
    for (const auto& p : outline) points.push_back({p[0], p[1], z});
  const std::uint32_t n = static_cast<std::uint32_t>(outline.size());
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    triangles.push_back({i, j, n + j});
    triangles.push_back({i, n + j, n + i});
  }
  for (std::uint32_t i = 1; i + 1 < n; ++i) {  // the caps, fans from the first corner
    triangles.push_back({0, i + 1, i});
    triangles.push_back({n, n + i, n + i + 1});
  }
  return mesh::build_from_triangles(points, triangles);
}

TEST(RemeshFidelity, NarrowChamferStaysWithinTwiceEpsilon) {
  {
    SCOPED_TRACE("chamfer 0.01");
    expect_within_twice_epsilon(chamfered_box(0.01), {0.0005});
  }
  {
    SCOPED_TRACE("chamfer 0.03");
    expect_within_twice_epsilon(chamfered_box(0.03), {0.0001});
  }
}

// The fidelity splits grow with a finer tolerance, never with a coarser one. Within the sweep's
// slack (scripts/sweep_remesh.py: 1 % + 5 vertices): where the max length decides, as on most of
// the pyramid, the count moves by a few vertices either way.
TEST(RemeshFidelity, CoarserEpsilonGivesNoMoreVertices) {
  for (const SurfaceMesh& input : {long_pyramid(), mesh::make_icosphere(0)}) {
    double finer = 1e300;
    for (const double epsilon : {0.0001, 0.0005, 0.002, 0.01}) {
      SCOPED_TRACE(testing::Message() << "epsilon " << epsilon);
      const double n = double(remeshed(input, epsilon, 0.0002).mesh.n_vertices());
      EXPECT_LE(n, 1.01 * finer + 5);
      finer = n;
    }
  }
}

// A 1 x 1 x 0.01 plate of 6 x 6 squares twisted by half a turn about its long axis: coarse edges
// whose midpoints lie well off the curved sheets, 0.01 apart. A fidelity split used to put its
// vertex on the reference unchecked, pushing the new fan through the other sheet: 16 crossing
// pairs at epsilon 0.01 % (the CGAL elk, femur, diplodocus, b9_mesh and ChineseDragon-10kv at
// epsilon 0.01-0.05 %: 12 sweep runs with 3 to 27 pairs). Now the crossing guard checks it.
SurfaceMesh twisted_thin_plate() {
  SurfaceMesh m = mesh::make_box(6, 6, 1, 1.0, 1.0, 0.01);
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (mesh::Vertex v : m.vertices())
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], m.position(v)[k]);
      hi[k] = std::max(hi[k], m.position(v)[k]);
    }
  for (mesh::Vertex v : m.vertices()) {
    Point& p = m.position(v);
    const double angle = M_PI * (p.x - lo[0]) / (hi[0] - lo[0]);
    const double y = p.y - 0.5 * (lo[1] + hi[1]), z = p.z - 0.5 * (lo[2] + hi[2]);
    p.y = y * std::cos(angle) - z * std::sin(angle);
    p.z = y * std::sin(angle) + z * std::cos(angle);
  }
  return m;
}

TEST(RemeshFidelity, SplitsOnATwistedThinPlateCrossNothing) {
  if (test::kSanitizedBuild) GTEST_SKIP() << "two remeshes to 30k vertices, minutes under ASan: the Release ctest runs it";
  const SurfaceMesh input = twisted_thin_plate();
  ASSERT_EQ(geometry::self_intersections(input, 1000).pairs.size(), 0u);
  for (const double epsilon : {0.0001, 0.0005}) {
    SCOPED_TRACE(testing::Message() << "epsilon " << epsilon);
    const Remeshed r = remeshed(input, epsilon, 0.0002);
    EXPECT_NO_THROW(r.mesh.validate());
    EXPECT_EQ(geometry::self_intersections(r.mesh, 1000).pairs.size(), 0u);
  }
}

}  // namespace

namespace {

// A 1 x 0.6 x 0.25 box as a CAD exporter may tessellate it: each face fanned from a point just
// inside one of its sides (offset by `inset` of the face's width), so that every face has two
// caps of about half a degree along that side, a sharp edge of the box.
SurfaceMesh box_with_capped_faces(double inset) {
  const double sx = 1.0, sy = 0.6, sz = 0.25;
  std::vector<std::array<double, 3>> points;
  for (double x : {0.0, sx})
    for (double y : {0.0, sy})
      for (double z : {0.0, sz}) points.push_back({x, y, z});
  auto corner = [](int x, int y, int z) { return static_cast<std::uint32_t>(4 * x + 2 * y + z); };
  // Each face's corners counter-clockwise seen from outside; the fan's centre lies by its first side.
  const std::uint32_t faces[6][4] = {
      {corner(0, 0, 0), corner(0, 1, 0), corner(1, 1, 0), corner(1, 0, 0)},
      {corner(0, 0, 1), corner(1, 0, 1), corner(1, 1, 1), corner(0, 1, 1)},
      {corner(0, 0, 0), corner(1, 0, 0), corner(1, 0, 1), corner(0, 0, 1)},
      {corner(0, 1, 0), corner(0, 1, 1), corner(1, 1, 1), corner(1, 1, 0)},
      {corner(0, 0, 0), corner(0, 0, 1), corner(0, 1, 1), corner(0, 1, 0)},
      {corner(1, 0, 0), corner(1, 1, 0), corner(1, 1, 1), corner(1, 0, 1)}};
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (const auto& q : faces) {
    std::array<double, 3> centre;
    for (int k = 0; k < 3; ++k)
      centre[k] = 0.5 * (points[q[0]][k] + points[q[1]][k]) + inset * (points[q[3]][k] - points[q[0]][k]);
    points.push_back(centre);
    const auto c = static_cast<std::uint32_t>(points.size() - 1);
    for (int i = 0; i < 4; ++i) triangles.push_back({q[i], q[(i + 1) % 4], c});
  }
  return mesh::build_from_triangles(points, triangles);
}

}  // namespace

// The input's slivers under a degree are cleaned up before the first iteration, and that clean-up
// may not reshape the surface: its repairs were held to a tenth of the tolerance at the sharp
// edges (safety.cpp) but to four tolerances by the fidelity check, which let them flip the box's
// edges under the caps. Before: 0.86 % and 1.47 % of the diagonal at epsilon 0.05 % and 0.2 %.
void expect_capped_box_within_target(double inset) {
  const SurfaceMesh input = box_with_capped_faces(inset);
  for (const double epsilon : {0.0005, 0.002}) {
    SCOPED_TRACE(testing::Message() << "epsilon " << epsilon);
    const Remeshed r = remeshed(input, epsilon, 0.002);
    EXPECT_LE(r.hausdorff_rel, 2 * std::max(epsilon, 0.001));  // the min length 0.2 % wins below 0.1 %
    EXPECT_NO_THROW(r.mesh.validate());
  }
}

TEST(RemeshFidelity, CleanupOfCapsAlongASharpEdgeKeepsTheEdge) { expect_capped_box_within_target(0.01); }

// Caps of a tenth of a degree along the box's edges: the coverage check sampled a sharp edge
// only where the triangles on both sides were wide enough for a remeshed triangle to cut it
// deeply, and a cap's height said it was not (before: 0.79 % of the diagonal at epsilon 0.05 %).
// The flat face beyond the cap counts.
TEST(RemeshFidelity, SharpEdgeUnderThinCapsIsCovered) { expect_capped_box_within_target(0.002); }

namespace {

// The surface of a union of unit cubes (occupied(i, j, k) on an n^3 grid), every square face
// split in two: a voxel model, flat sides meeting at right-angled steps.
template <typename Occupied>
SurfaceMesh voxel_surface(int n, Occupied occupied) {
  auto inside = [&](int i, int j, int k) {
    return i >= 0 && j >= 0 && k >= 0 && i < n && j < n && k < n && occupied(i, j, k);
  };
  std::vector<std::array<double, 3>> points;
  std::vector<std::uint32_t> index((n + 1) * (n + 1) * (n + 1), UINT32_MAX);
  auto corner = [&](int i, int j, int k) {
    std::uint32_t& id = index[(i * (n + 1) + j) * (n + 1) + k];
    if (id == UINT32_MAX) {
      id = static_cast<std::uint32_t>(points.size());
      points.push_back({double(i), double(j), double(k)});
    }
    return id;
  };
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        if (!inside(i, j, k)) continue;
        for (int axis = 0; axis < 3; ++axis)
          for (int side : {-1, 1}) {
            int c[3] = {i, j, k};
            c[axis] += side;
            if (inside(c[0], c[1], c[2])) continue;
            // The square between the cube and its empty neighbour, counter-clockwise from outside.
            int o[3] = {i, j, k};
            if (side > 0) ++o[axis];
            int u[3] = {0, 0, 0}, w[3] = {0, 0, 0};
            u[(axis + 1) % 3] = 1;
            w[(axis + 2) % 3] = 1;
            std::uint32_t q[4] = {corner(o[0], o[1], o[2]), corner(o[0] + u[0], o[1] + u[1], o[2] + u[2]),
                                  corner(o[0] + u[0] + w[0], o[1] + u[1] + w[1], o[2] + u[2] + w[2]),
                                  corner(o[0] + w[0], o[1] + w[1], o[2] + w[2])};
            if (side < 0) std::swap(q[1], q[3]);
            triangles.push_back({q[0], q[1], q[2]});
            triangles.push_back({q[0], q[2], q[3]});
          }
      }
  return mesh::build_from_triangles(points, triangles);
}

}  // namespace

// A flight of 8 steps, 4 wide, as voxels: its sides are flat, split into unit squares, and an
// edge from one side to a step two creases away can lie on the plane of a third side without
// being near it. The planes' estimate of segment_strays took such an edge for one on the surface
// (cgal/tripod at epsilon 0.05 %: 2.8 x the target); here at epsilon 0.2 % the remesh ended 0.52 %
// of the diagonal off, 1.3 x the target. The estimate now holds only for ends on one triangle or
// on two neighbours; the others are measured.
TEST(RemeshFidelity, ChordsAcrossTwoCreasesAreMeasured) {
  const SurfaceMesh stairs = voxel_surface(8, [](int i, int j, int k) { return j < 8 - i && k < 4; });
  const Remeshed r = remeshed(stairs, 0.002, 0.002);
  EXPECT_LE(r.hausdorff_rel, 2 * 0.002);
  EXPECT_NO_THROW(r.mesh.validate());
  EXPECT_EQ(geometry::self_intersections(r.mesh, 1000).pairs.size(), 0u);
}

// Two coarse CAD parts of the CGAL corpus at epsilon 0.2 % (skipped without it): an edge from a
// face beside an inner corner of the part to another face of that corner, 9 degrees from it, ran
// across the notch where two walls rise from the corner. The ends' normals, nearly parallel, told
// the fidelity check that the surface between hardly turns, but the corner's fan turns by 97
// degrees: tripod ended 0.50 % of the diagonal off, corner_with_hole 0.42 % (the target: 0.4 %).
// The fan's largest turn counts now (fidelity.cpp, segment_strays): 0.31 % and 0.23 %.
TEST(RemeshFidelity, ChordsPastAnInnerCornerAreMeasured) {
  for (const char* name : {"tripod.off", "corner_with_hole.off"}) {
    SCOPED_TRACE(name);
    const std::string path = test::cgal_mesh(name);
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not found (scripts/fetch-cgal-meshes.sh)";
    const SurfaceMesh input = io::load_mesh(path);
    const Remeshed r = remeshed(input, 0.002, 0.002);
    EXPECT_LE(r.hausdorff_rel, 2 * 0.002);
    EXPECT_NO_THROW(r.mesh.validate());
    EXPECT_EQ(geometry::self_intersections(r.mesh, 1000).pairs.size(), 0u);
  }
}

namespace {

// A D-shaped prism as a CAD exporter writes it: a half cylinder of radius 1 over theta in [0, pi]
// (n strips, each one quad as long as the prism split into two long slivers), the flat face y = 0
// and two half-disk caps fanned from a corner.
SurfaceMesh d_shaped_prism(std::uint32_t n, double length) {
  std::vector<std::array<double, 3>> points;
  for (const double z : {0.0, length})
    for (std::uint32_t i = 0; i <= n; ++i) {
      const double t = M_PI * i / n;
      points.push_back({std::cos(t), std::sin(t), z});
    }
  const std::uint32_t m = n + 1;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (std::uint32_t i = 0; i < n; ++i) {
    triangles.push_back({i, i + 1, m + i + 1});
    triangles.push_back({i, m + i + 1, m + i});
  }
  triangles.push_back({n, 0, m});
  triangles.push_back({n, m, m + n});
  for (std::uint32_t i = 1; i < n; ++i) {
    triangles.push_back({0, i + 1, i});
    triangles.push_back({m, m + i, m + i + 1});
  }
  return mesh::build_from_triangles(points, triangles);
}

}  // namespace

// polish() moves the corners of poor triangles (sliver placement). A fan already off the input
// after the last iteration was allowed any new place, and on the prism at epsilon 0.2 % a move
// took an edge across the right-angled crease from 2 to 4.5 tolerances off: Hausdorff 1.0 % of
// the diagonal, 2.5 x the target, all of it made by polish. Now a straying fan may move only where
// it strays no farther.
TEST(RemeshFidelity, PolishTakesNoEdgeFartherFromTheInput) {
  const SurfaceMesh input = d_shaped_prism(48, 4.0);
  SurfaceMesh m = input;
  remesh::RemeshOptions o = remesh::default_options_for(m);
  o.epsilon = 0.002 * remesh::bounding_box_diagonal(m);
  o.min_length = 0.0002 * remesh::bounding_box_diagonal(m);
  double before = 0, after = 0;
  {
    // remesh::remesh's steps, measured before its polish().
    remesh::Remesher remesher(m, o);
    remesher.keep_guard_grid();
    size_t ordered_slots = m.faces_size();
    for (int i = 0; i < o.iterations; ++i) {
      remesher.iterate(i + 2 >= o.iterations);
      remesher.tidy_between_iterations(ordered_slots);
    }
    SurfaceMesh unpolished = m;
    unpolished.garbage_collection();
    before = geometry::distance_between(unpolished, input, 20000).hausdorff;
    remesher.polish();
  }
  m.garbage_collection();
  ASSERT_NO_THROW(m.validate());
  after = geometry::distance_between(m, input, 20000).hausdorff;
  EXPECT_LE(after, std::max(before, 2 * o.epsilon) + 1e-12) << "before polish " << before;
}
