// Connectivity tests of SurfaceMesh: construction from soups, circulators, edits, and a
// property test of thousands of random edits with validate() after each one.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include "io/load_mesh.h"
#include "mesh/build_from_triangles.h"
#include "mesh/primitives.h"
#include "mesh/surface_mesh.h"
#include "test_build.h"

using namespace adasculpt;
using namespace adasculpt::mesh;

namespace {

int euler_characteristic(const SurfaceMesh& m) {
  return int(m.n_vertices()) - int(m.n_edges()) + int(m.n_faces());
}

int boundary_loops(const SurfaceMesh& m) {
  std::vector<char> seen(m.halfedges_size(), 0);
  int loops = 0;
  for (Halfedge h : m.halfedges()) {
    if (!m.is_boundary(h) || seen[h.idx]) continue;
    ++loops;
    Halfedge g = h;
    do {
      seen[g.idx] = 1;
      g = m.next(g);
    } while (g != h);
  }
  return loops;
}

}  // namespace

TEST(SurfaceMesh, IcosphereIsClosedGenusZero) {
  SurfaceMesh m = make_icosphere(2);
  EXPECT_EQ(m.n_faces(), 320u);
  EXPECT_EQ(m.n_vertices(), 162u);
  EXPECT_EQ(euler_characteristic(m), 2);
  EXPECT_EQ(boundary_loops(m), 0);
  EXPECT_NO_THROW(m.validate());
  size_t valence_sum = 0;
  for (Vertex v : m.vertices()) valence_sum += m.valence(v);
  EXPECT_EQ(valence_sum, 2 * m.n_edges());
}

TEST(SurfaceMesh, GridHasOneBoundaryLoop) {
  SurfaceMesh m = make_grid(4);
  EXPECT_EQ(m.n_vertices(), 25u);
  EXPECT_EQ(m.n_faces(), 32u);
  EXPECT_EQ(boundary_loops(m), 1);
  EXPECT_EQ(euler_characteristic(m), 1);
  int boundary_vertices = 0;
  for (Vertex v : m.vertices()) boundary_vertices += m.is_boundary(v);
  EXPECT_EQ(boundary_vertices, 16);
}

TEST(SurfaceMesh, BoxIsClosed) {
  SurfaceMesh m = make_box(2, 3, 4);
  EXPECT_EQ(euler_characteristic(m), 2);
  EXPECT_EQ(boundary_loops(m), 0);
}

TEST(SurfaceMesh, FaceCirculatorSkipsBoundaryGap) {
  SurfaceMesh m = make_grid(2);
  for (Vertex v : m.vertices()) {
    size_t faces = 0;
    for (Face f : m.faces(v)) {
      EXPECT_TRUE(f.is_valid());
      ++faces;
    }
    EXPECT_EQ(faces, m.is_boundary(v) ? m.valence(v) - 1 : m.valence(v));
  }
}

TEST(BuildFromTriangles, SplitsNonManifoldVertex) {
  // Two triangles touching at vertex 0 only.
  std::vector<std::array<double, 3>> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
  std::vector<std::array<std::uint32_t, 3>> t = {{0, 1, 2}, {0, 3, 4}};
  BuildReport report;
  SurfaceMesh m = build_from_triangles(p, t, &report);
  EXPECT_EQ(m.n_vertices(), 6u);
  EXPECT_EQ(report.split_vertices, 1u);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("non-manifold"), std::string::npos);
}

// The edges are paired by a counting sort on their lower vertex, then a sort of each vertex's
// few edges; a fan's centre has many (this one 600, with the other corners in shuffled order).
// Every edge must still find its twin: one disc, 600 border edges, 600 inner ones.
TEST(BuildFromTriangles, PairsTheEdgesOfAVertexWithHundredsOfThem) {
  constexpr std::uint32_t kFan = 600;
  std::vector<std::array<double, 3>> p = {{0, 0, 0}};
  std::vector<std::uint32_t> slot(kFan);  // rim position i gets point index slot[i]
  for (std::uint32_t i = 0; i < kFan; ++i) slot[i] = 1 + (i * 7919u) % kFan;
  p.resize(kFan + 1);
  for (std::uint32_t i = 0; i < kFan; ++i) {
    const double a = 2 * M_PI * i / kFan;
    p[slot[i]] = {std::cos(a), std::sin(a), 0};
  }
  std::vector<std::array<std::uint32_t, 3>> t;
  for (std::uint32_t i = 0; i < kFan; ++i) t.push_back({0, slot[i], slot[(i + 1) % kFan]});
  const SurfaceMesh m = build_from_triangles(p, t);
  ASSERT_NO_THROW(m.validate());
  EXPECT_EQ(m.n_vertices(), kFan + 1);
  EXPECT_EQ(m.n_edges(), 2 * kFan);
  EXPECT_EQ(euler_characteristic(m), 1);
  EXPECT_EQ(m.valence(Vertex(0)), kFan);
}

TEST(BuildFromTriangles, RejectsNonManifoldEdgeNamingVertices) {
  std::vector<std::array<double, 3>> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  std::vector<std::array<std::uint32_t, 3>> t = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  try {
    build_from_triangles(p, t);
    FAIL() << "expected a TopologyError";
  } catch (const TopologyError& e) {
    EXPECT_STREQ(e.what(), "non-manifold edge between vertices 0 and 1 (3 faces)");
  }
}

TEST(BuildFromTriangles, ReversesAFaceThatDisagreesWithItsNeighbour) {
  // Both faces run the edge 0 -> 1: one of them is reversed (mesh_orient_faces_test has more).
  std::vector<std::array<double, 3>> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}};
  std::vector<std::array<std::uint32_t, 3>> t = {{0, 1, 2}, {0, 1, 3}};
  BuildReport report;
  SurfaceMesh m = build_from_triangles(p, t, &report);
  EXPECT_EQ(m.n_faces(), 2u);
  EXPECT_EQ(report.reoriented_faces, 1u);
  EXPECT_EQ(report.warnings.size(), 1u);
}

TEST(BuildFromTriangles, DropsRepeatedIndexFacesAndRejectsEmpty) {
  std::vector<std::array<double, 3>> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  BuildReport report;
  SurfaceMesh m = build_from_triangles(p, {{0, 1, 2}, {0, 0, 1}}, &report);
  EXPECT_EQ(m.n_faces(), 1u);
  EXPECT_EQ(report.dropped_faces, 1u);
  EXPECT_THROW(build_from_triangles(p, {{0, 0, 1}}), TopologyError);
  EXPECT_THROW(build_from_triangles(p, {{0, 1, 7}}), TopologyError);
}

TEST(SurfaceMesh, SplitCollapseFlipKeepCounts) {
  SurfaceMesh m = make_icosphere(1);
  const size_t v0 = m.n_vertices(), f0 = m.n_faces();
  Vertex v = m.split(Edge(0), Point(0.0));
  m.validate();
  EXPECT_EQ(m.valence(v), 4u);
  EXPECT_EQ(m.n_vertices(), v0 + 1);
  EXPECT_EQ(m.n_faces(), f0 + 2);
  Halfedge h = m.halfedge(v);
  ASSERT_TRUE(m.is_collapse_ok(h));
  m.collapse(h);
  m.validate();
  EXPECT_EQ(m.n_vertices(), v0);
  EXPECT_EQ(m.n_faces(), f0);
  Edge e(5);
  ASSERT_TRUE(m.is_flip_ok(e));
  m.flip(e);
  m.validate();
  m.garbage_collection();
  m.validate();
  EXPECT_EQ(m.n_vertices(), m.vertices_size());
  EXPECT_EQ(euler_characteristic(m), 2);
}

TEST(SurfaceMesh, BoundarySplitAndCollapse) {
  SurfaceMesh m = make_grid(3);
  Edge boundary_edge;
  for (Edge e : m.edges())
    if (m.is_boundary(e)) {
      boundary_edge = e;
      break;
    }
  Vertex v = m.split(boundary_edge, Point(0.0));
  m.validate();
  EXPECT_TRUE(m.is_boundary(v));
  EXPECT_EQ(m.valence(v), 3u);
  EXPECT_EQ(boundary_loops(m), 1);
}

TEST(SurfaceMesh, CollapseRefusesTetrahedronEdge) {
  std::vector<std::array<double, 3>> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  SurfaceMesh m = build_from_triangles(p, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}});
  for (Halfedge h : m.halfedges()) EXPECT_FALSE(m.is_collapse_ok(h));
  for (Edge e : m.edges()) EXPECT_FALSE(m.is_flip_ok(e));
}

TEST(SurfaceMesh, CopyIsDeepAndPropertiesFollowGarbageCollection) {
  SurfaceMesh m = make_icosphere(1);
  auto tag = m.add_vertex_property<int>("v:tag", -1);
  for (Vertex v : m.vertices()) tag[v] = int(v.idx);
  SurfaceMesh copy = m;
  copy.position(Vertex(0)) = Point(9.0);
  EXPECT_NE(m.position(Vertex(0)).x, 9.0);
  // Collapse vertex 0 away; after compaction the tags still name the original vertices.
  Halfedge h = m.halfedge(Vertex(0));
  ASSERT_TRUE(m.is_collapse_ok(h));
  Point p3 = m.position(Vertex(3));
  m.collapse(h);
  m.garbage_collection();
  m.validate();
  for (Vertex v : m.vertices()) {
    EXPECT_NE(tag[v], 0);
    if (tag[v] == 3) {
      EXPECT_EQ(m.position(v), p3);
    }
  }
  auto copied_tag = copy.get_vertex_property<int>("v:tag");
  ASSERT_TRUE(copied_tag.is_valid());
  EXPECT_EQ(copied_tag[Vertex(0)], 0);
}

// A sculpting stroke adds its arrays (remesher sizing, flags) to a loaded mesh and then splits
// edges: neither the mesh's arrays nor the added ones may be reallocated (copied) by the first
// splits, and all of them keep the values they had.
TEST(SurfaceMesh, ArraysHaveRoomForTheFirstSplitsOfAStroke) {
  const io::PolygonSoup soup = io::soup_from_mesh(make_icosphere(3));
  SurfaceMesh m = build_from_triangles(soup.points, soup.triangles);
  auto sizing = m.add_vertex_property<double>("test:sizing", 0.5);
  auto flags = m.add_edge_property<std::uint8_t>("test:flag", 1);
  const Point* positions_before = m.positions().data();
  const double* sizing_before = &sizing[Vertex(0)];
  const std::uint8_t* flags_before = &flags[mesh::Edge(0)];
  const size_t splits = m.n_faces() / 20;  // within the eighth more build_from_triangles leaves
  for (size_t i = 0; i < splits; ++i) {
    const mesh::Edge e(static_cast<mesh::Index>(i * 7 % m.edges_size()));
    m.split(e, 0.5 * (m.position(m.vertex(e, 0)) + m.position(m.vertex(e, 1))));
  }
  m.validate();
  EXPECT_EQ(m.positions().data(), positions_before);
  EXPECT_EQ(&sizing[Vertex(0)], sizing_before);
  EXPECT_EQ(&flags[mesh::Edge(0)], flags_before);
  EXPECT_EQ(sizing[Vertex(0)], 0.5);
  EXPECT_EQ(sizing[Vertex(static_cast<mesh::Index>(m.vertices_size() - 1))], 0.5);
  // Past the room, everything grows together and keeps its values.
  const size_t more = m.n_faces();
  for (size_t i = 0; i < more; ++i) {
    const mesh::Edge e(static_cast<mesh::Index>(3 * i % m.edges_size()));
    m.split(e, 0.5 * (m.position(m.vertex(e, 0)) + m.position(m.vertex(e, 1))));
  }
  m.validate();
  EXPECT_EQ(sizing[Vertex(0)], 0.5);
  EXPECT_EQ(flags[mesh::Edge(static_cast<mesh::Index>(m.edges_size() - 1))], 1);
}

// The property test the foundation rests on: random splits, collapses and flips on a sphere
// and on an open grid, validate() after every one, topology invariants checked throughout.
class RandomEdits : public ::testing::TestWithParam<int> {};

TEST_P(RandomEdits, TenThousandOperationsKeepTheMeshValid) {
  const bool open = GetParam() == 1;
  SurfaceMesh m = open ? make_grid(8) : make_icosphere(2);
  const int chi = euler_characteristic(m);
  const int loops = boundary_loops(m);
  std::mt19937 rng(1234 + GetParam());
  int splits = 0, collapses = 0, flips = 0;
  // 10,000 in Release; a quarter under the sanitizers (test_build.h).
  const int steps = test::operations_for_this_build(10000);
  for (int step = 0; step < steps; ++step) {
    std::vector<Edge> live;
    // Sample a random live edge (retry on deleted slots).
    Edge e;
    for (int tries = 0; tries < 1000 && !e.is_valid(); ++tries) {
      Edge c(std::uniform_int_distribution<Index>(0, Index(m.edges_size() - 1))(rng));
      if (!m.is_deleted(c)) e = c;
    }
    ASSERT_TRUE(e.is_valid());
    int op = std::uniform_int_distribution<int>(0, 2)(rng);
    // Keep the mesh between 100 and 2000 faces so all three operations stay exercised.
    if (m.n_faces() < 100) op = 0;
    if (m.n_faces() > 2000) op = 1;
    if (op == 0) {
      Point mid = 0.5 * (m.position(m.vertex(e, 0)) + m.position(m.vertex(e, 1)));
      m.split(e, mid);
      ++splits;
    } else if (op == 1) {
      Halfedge h = m.halfedge(e, std::uniform_int_distribution<unsigned>(0, 1)(rng));
      if (!m.is_collapse_ok(h)) continue;
      m.collapse(h);
      ++collapses;
    } else {
      if (!m.is_flip_ok(e)) continue;
      m.flip(e);
      ++flips;
    }
    ASSERT_NO_THROW(m.validate()) << "after step " << step << " (op " << op << ")";
    ASSERT_EQ(euler_characteristic(m), chi) << "step " << step;
    if (step % 500 == 0) {
      // Every other time the compaction in space order (sort_in_space): any order of the slots.
      if (step % 1000 == 0)
        m.garbage_collection();
      else
        m.sort_in_space();
      ASSERT_NO_THROW(m.validate());
      ASSERT_EQ(boundary_loops(m), loops);
    }
  }
  EXPECT_GT(splits, steps / 10);
  EXPECT_GT(collapses, steps / 10);
  EXPECT_GT(flips, steps / 10);
  EXPECT_EQ(boundary_loops(m), loops);
}

INSTANTIATE_TEST_SUITE_P(SphereAndGrid, RandomEdits, ::testing::Values(0, 1));

namespace {
// The faces as sorted triples of corner positions: the surface, whatever the slots.
std::vector<std::array<std::array<double, 3>, 3>> face_set(const SurfaceMesh& m) {
  std::vector<std::array<std::array<double, 3>, 3>> out;
  for (Face f : m.faces()) {
    Vertex c[3];
    m.face_vertices(f, c);
    std::array<std::array<double, 3>, 3> t;
    for (int i = 0; i < 3; ++i) t[i] = {m.position(c[i]).x, m.position(c[i]).y, m.position(c[i]).z};
    // The cyclic rotation that starts at the smallest corner keeps the orientation.
    const int first = int(std::min_element(t.begin(), t.end()) - t.begin());
    std::rotate(t.begin(), t.begin() + first, t.end());
    out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The mean difference of the slots at the ends of an edge, over the edges: how far apart in
// memory the neighbours of a fan lie.
double mean_edge_slot_gap(const SurfaceMesh& m) {
  double sum = 0;
  for (Edge e : m.edges()) sum += std::abs(double(m.vertex(e, 0).idx) - double(m.vertex(e, 1).idx));
  return sum / double(m.n_edges());
}
}  // namespace

TEST(SurfaceMeshSortInSpace, KeepsTheSurfaceAndItsPropertiesAndPutsNeighboursNearInMemory) {
  // A sphere with 2,000 random midpoint splits: the new vertices at the end of the arrays,
  // their fans scattered over them, and some collapses for garbage.
  SurfaceMesh m = make_icosphere(3);
  std::mt19937 rng(7);
  for (int i = 0; i < 2000; ++i) {
    Edge e(std::uniform_int_distribution<Index>(0, Index(m.edges_size() - 1))(rng));
    if (m.is_deleted(e)) continue;
    if (i % 5 == 4) {
      const Halfedge h = m.halfedge(e, 0);
      if (m.is_collapse_ok(h)) m.collapse(h);
      continue;
    }
    m.split(e, 0.5 * (m.position(m.vertex(e, 0)) + m.position(m.vertex(e, 1))));
  }
  ASSERT_TRUE(m.has_garbage());
  // Properties that name their element by geometry, to see that each follows its element.
  auto vtag = m.add_vertex_property<Point>("test:vertex", Point(0.0));
  auto ftag = m.add_face_property<Point>("test:face", Point(0.0));
  auto etag = m.add_edge_property<Point>("test:edge", Point(0.0));
  for (Vertex v : m.vertices()) vtag[v] = m.position(v);
  for (Face f : m.faces()) {
    Vertex c[3];
    m.face_vertices(f, c);
    ftag[f] = m.position(c[0]) + m.position(c[1]) + m.position(c[2]);
  }
  for (Edge e : m.edges()) etag[e] = m.position(m.vertex(e, 0)) + m.position(m.vertex(e, 1));
  const auto surface = face_set(m);
  SurfaceMesh collected = m;
  collected.garbage_collection();

  m.sort_in_space();
  ASSERT_NO_THROW(m.validate());
  EXPECT_FALSE(m.has_garbage());
  EXPECT_EQ(m.n_vertices(), collected.n_vertices());
  EXPECT_EQ(m.vertices_size(), m.n_vertices());
  EXPECT_EQ(face_set(m), surface);
  for (Vertex v : m.vertices()) EXPECT_EQ(vtag[v], m.position(v));
  for (Face f : m.faces()) {
    Vertex c[3];
    m.face_vertices(f, c);
    EXPECT_EQ(ftag[f], m.position(c[0]) + m.position(c[1]) + m.position(c[2]));
  }
  for (Edge e : m.edges()) {
    const Point sum = m.position(m.vertex(e, 0)) + m.position(m.vertex(e, 1));
    EXPECT_EQ(etag[e], sum);
  }
  // Neighbours lie near each other in memory: a garbage collection keeps the splits' scattered
  // order, the sort brings the edges' ends several times closer.
  const double gap_collected = mean_edge_slot_gap(collected), gap_sorted = mean_edge_slot_gap(m);
  std::printf("mean slot gap of an edge's ends: %.0f collected, %.0f sorted (%zu vertices)\n", gap_collected,
              gap_sorted, m.n_vertices());
  EXPECT_LT(gap_sorted, 0.25 * gap_collected);
  // And the order is deterministic: sorting again changes nothing.
  const std::vector<Point> once(m.positions().begin(), m.positions().begin() + m.vertices_size());
  m.sort_in_space();
  EXPECT_EQ(std::vector<Point>(m.positions().begin(), m.positions().begin() + m.vertices_size()), once);
}
