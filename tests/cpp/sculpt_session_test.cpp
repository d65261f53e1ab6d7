// Session: grabs interleaved with remeshing, undo/redo exactness, the sculpting scenarios of the
// paper (a tail pulled out of a sphere, a square bar twisted with sharp features kept).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "geometry/quality.h"
#include "mesh/primitives.h"
#include "sculpt/session.h"
#include "sculpt/session_file.h"
#include "test_build.h"

using namespace adasculpt;
using mesh::Vertex;

namespace {

// Bitwise positions and the exact connectivity (slot by slot).
::testing::AssertionResult same_compact_mesh(const mesh::SurfaceMesh& a, const mesh::SurfaceMesh& b) {
  if (a.vertices_size() != b.vertices_size() || a.halfedges_size() != b.halfedges_size() ||
      a.faces_size() != b.faces_size())
    return ::testing::AssertionFailure() << "sizes differ: " << a.vertices_size() << "/" << b.vertices_size()
                                         << " vertices, " << a.faces_size() << "/" << b.faces_size() << " faces";
  for (size_t i = 0; i < a.vertices_size(); ++i) {
    const Vertex v(static_cast<mesh::Index>(i));
    if (std::memcmp(&a.position(v), &b.position(v), sizeof(Point)) != 0)
      return ::testing::AssertionFailure() << "position of vertex " << i << " differs";
    if (a.halfedge(v) != b.halfedge(v) || a.is_deleted(v) != b.is_deleted(v))
      return ::testing::AssertionFailure() << "vertex " << i << " connectivity differs";
  }
  for (size_t i = 0; i < a.halfedges_size(); ++i) {
    const mesh::Halfedge h(static_cast<mesh::Index>(i));
    if (a.to_vertex(h) != b.to_vertex(h) || a.next(h) != b.next(h) || a.face(h) != b.face(h))
      return ::testing::AssertionFailure() << "halfedge " << i << " differs";
  }
  for (size_t i = 0; i < a.faces_size(); ++i) {
    const mesh::Face f(static_cast<mesh::Index>(i));
    if (a.halfedge(f) != b.halfedge(f)) return ::testing::AssertionFailure() << "face " << i << " differs";
  }
  return ::testing::AssertionSuccess();
}

// The same, after compaction: a stroke or a grab may leave deleted slots (the session compacts
// them only once they add up), while undo and redo restore compacted meshes.
::testing::AssertionResult same_mesh(const mesh::SurfaceMesh& a, const mesh::SurfaceMesh& b) {
  if (!a.has_garbage() && !b.has_garbage()) return same_compact_mesh(a, b);
  mesh::SurfaceMesh ca = a, cb = b;
  ca.garbage_collection();
  cb.garbage_collection();
  return same_compact_mesh(ca, cb);
}

deform::HandleTransform translate(Vec3 t) {
  deform::HandleTransform x;
  x.translation = t;
  return x;
}

void drag(sculpt::Session& s, Point c, double hr, double rr, const deform::HandleTransform& total, int substeps) {
  s.grab_begin(c, hr, rr);
  for (int i = 1; i <= substeps; ++i) {
    const double f = double(i) / substeps;
    deform::HandleTransform t;
    t.translation = f * total.translation;
    t.rotation = glm::slerp(glm::dquat(1, 0, 0, 0), total.rotation, f);
    t.scale = 1 + f * (total.scale - 1);
    s.grab_drag(t);
  }
  s.grab_end();
}

}  // namespace

TEST(SculptSession, SettingsAcceptPercentAndNameBadFields) {
  sculpt::Session s;
  s.load(mesh::make_icosphere(2));
  const double diag = s.settings()["diagonal"];
  EXPECT_NEAR(s.settings()["epsilon"].get<double>(), 0.0005 * diag, 1e-12);
  s.set_settings({{"epsilon", "0.1%"}, {"max_length", 0.3}, {"features", 40}});
  EXPECT_NEAR(s.settings()["epsilon"].get<double>(), 0.001 * diag, 1e-12);
  EXPECT_EQ(s.settings()["max_length"].get<double>(), 0.3);
  EXPECT_EQ(s.settings()["features"].get<double>(), 40);
  try {
    s.set_settings({{"min_length", "x"}});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'min_length'"), std::string::npos);
  }
  EXPECT_THROW(s.set_settings({{"min_length", 1.0}, {"max_length", 0.5}}), std::invalid_argument);
  EXPECT_EQ(s.settings()["max_length"].get<double>(), 0.3);  // unchanged after an error
}

// guard_crossings switches the region crossing guard of strokes and grabs (RemeshRegionGuard.*
// tests what it does); a preference, so a load keeps it, and session files carry it.
TEST(SculptSession, GuardCrossingsIsASettingKeptThroughLoads) {
  sculpt::Session s;
  s.load(mesh::make_icosphere(2));
  EXPECT_FALSE(s.settings()["guard_crossings"].get<bool>());
  s.set_settings({{"guard_crossings", true}});
  EXPECT_TRUE(s.settings()["guard_crossings"].get<bool>());
  try {
    s.set_settings({{"guard_crossings", 1}, {"features", 30}});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'guard_crossings'"), std::string::npos);
  }
  EXPECT_EQ(s.settings()["features"].get<double>(), 0);  // nothing changed
  drag(s, Point(0, 0, 1), 0.1, 0.7, translate(Vec3(0, 0, 0.3)), 4);  // a remesher made with the guard
  EXPECT_NO_THROW(s.mesh().validate());
  s.load(mesh::make_icosphere(3));
  EXPECT_TRUE(s.settings()["guard_crossings"].get<bool>());
  const sculpt::SettingsPatch p = sculpt::parse_settings({{"guard_crossings", false}});
  ASSERT_TRUE(p.guard_crossings.has_value());
  EXPECT_EQ(sculpt::to_json(p), nlohmann::json({{"guard_crossings", false}}));
}

TEST(SculptSession, UndoReturnsTheExactInputRedoTheExactResult) {
  sculpt::Session s;
  s.load(mesh::make_icosphere(3));
  const mesh::SurfaceMesh input = s.mesh();
  drag(s, Point(0, 0, 1), 0.1, 0.7, translate(Vec3(0, 0, 0.6)), 8);
  drag(s, Point(1, 0, 0), 0.05, 0.5, translate(Vec3(0.3, 0.2, 0)), 5);
  deform::HandleTransform twist;
  twist.rotation = glm::angleAxis(1.0, Vec3(0, 0, 1));
  twist.scale = 1.3;
  drag(s, Point(0, 0, -1), 0.2, 0.8, twist, 6);
  s.mesh().validate();
  const mesh::SurfaceMesh result = s.mesh();
  EXPECT_FALSE(same_mesh(input, result));
  EXPECT_TRUE(s.undo());
  EXPECT_TRUE(s.undo());
  EXPECT_TRUE(s.undo());
  EXPECT_FALSE(s.can_undo());
  EXPECT_TRUE(same_mesh(s.mesh(), input));
  EXPECT_TRUE(s.redo() && s.redo() && s.redo());
  EXPECT_FALSE(s.redo());
  EXPECT_TRUE(same_mesh(s.mesh(), result));
}

TEST(SculptSession, ARemeshLeavesTheMeshInSpaceOrderAndUndoesExactly) {
  // A whole-mesh remesh appends its splits' vertices at the end of the arrays; the session sorts
  // the result in space (mesh/surface_mesh.h): the vertices follow a Z-order curve, so that the
  // fans the sculpting walks lie together in memory. Undo and redo stay exact to the slot.
  sculpt::Session s;
  s.load(mesh::make_icosphere(4));
  drag(s, Point(0, 0, 1), 0.1, 0.7, translate(Vec3(0, 0, 0.6)), 8);
  const mesh::SurfaceMesh before = s.mesh();
  s.remesh(2);
  const mesh::SurfaceMesh remeshed = s.mesh();
  remeshed.validate();
  mesh::SurfaceMesh resorted = remeshed;
  resorted.sort_in_space();
  EXPECT_TRUE(same_mesh(resorted, remeshed)) << "the remesh's result is already in space order";
  EXPECT_TRUE(s.undo());
  EXPECT_TRUE(same_mesh(s.mesh(), before));
  EXPECT_TRUE(s.redo());
  EXPECT_TRUE(same_mesh(s.mesh(), remeshed));
}

TEST(SculptSession, ChangesAndTimingsAreReported) {
  sculpt::Session s;
  s.load(mesh::make_icosphere(3));
  s.clear_changes();
  s.grab_begin(Point(0, 0, 1), 0.1, 0.6);
  s.grab_drag(translate(Vec3(0, 0, 0.1)));
  EXPECT_FALSE(s.changes().touched_vertices.empty());
  EXPECT_FALSE(s.changes().everything);
  EXPECT_GT(s.last_frame().total_ms, 0.0);
  EXPECT_GE(s.last_frame().total_ms, s.last_frame().field_ms);
  s.grab_end();
  Point hit;
  EXPECT_TRUE(s.pick(Point(0, 0, 5), Vec3(0, 0, -1), &hit));
  EXPECT_GT(hit.z, 1.0);
  EXPECT_FALSE(s.pick(Point(0, 0, 5), Vec3(0, 0, 1), &hit));
}

TEST(SculptSession, PullBendAndScaleATailOutOfASphere) {
  sculpt::Session s;
  s.load(mesh::make_icosphere(4));  // radius 1
  s.set_settings({{"epsilon", "0.1%"}, {"min_length", "0.5%"}, {"max_length", "8%"}});
  s.remesh(3);
  // Pull 3 radii out, in small steps (as a mouse drag).
  drag(s, Point(0, 0, 1), 0.15, 0.9, translate(Vec3(0, 0, 3.0)), 60);
  // Bend the tip sideways around the middle of the tail, then scale the tip.
  deform::HandleTransform bend;
  bend.rotation = glm::angleAxis(glm::radians(60.0), Vec3(0, 1, 0));
  bend.translation = Vec3(0.8, 0, -0.3);
  drag(s, Point(0, 0, 4.0), 0.2, 1.5, bend, 30);
  deform::HandleTransform grow;
  grow.scale = 1.8;
  Point tip(-1e9);
  for (Vertex v : s.mesh().vertices())
    if (s.mesh().position(v).z > tip.z) tip = s.mesh().position(v);
  drag(s, tip, 0.2, 0.7, grow, 20);
  s.mesh().validate();
  const geometry::QualityReport q = s.quality();
  double zmax = -1e9;
  for (Vertex v : s.mesh().vertices()) zmax = std::max(zmax, s.mesh().position(v).z);
  std::printf("tail: %zu vertices, z max %.2f, min angle %.1f, mean min angle %.1f, genus %d\n", q.vertices, zmax,
              q.min_angle_deg, q.mean_min_angle_deg, q.genus);
  EXPECT_GT(zmax, 2.5);  // a tail several radii long
  EXPECT_EQ(q.genus, 0);
  EXPECT_EQ(q.components, 1);
  EXPECT_EQ(q.boundary_loops, 0);
  EXPECT_GE(q.min_angle_deg, 20.0);
  EXPECT_GE(q.mean_min_angle_deg, 48.0);
}

TEST(SculptSession, TwistingASquareBarKeepsItsSharpEdges) {
  sculpt::Session s;
  s.load(mesh::make_box(4, 4, 16, 0.5, 0.5, 2.0));
  s.set_settings({{"features", 45}, {"epsilon", "0.1%"}, {"min_length", "1%"}, {"max_length", "4%"}});
  s.remesh(2);
  auto sharp_length = [&](double min_deg) {
    const mesh::SurfaceMesh& m = s.mesh();
    double total = 0;
    for (mesh::Edge e : m.edges()) {
      if (m.is_boundary(e)) continue;
      const mesh::Halfedge h0 = mesh::SurfaceMesh::halfedge(e, 0), h1 = mesh::SurfaceMesh::halfedge(e, 1);
      auto normal = [&](mesh::Halfedge h) {
        const Point& a = m.position(m.from_vertex(h));
        const Point& b = m.position(m.to_vertex(h));
        const Point& c = m.position(m.to_vertex(m.next(h)));
        return glm::normalize(glm::cross(b - a, c - a));
      };
      const double angle = glm::degrees(std::acos(std::clamp(glm::dot(normal(h0), normal(h1)), -1.0, 1.0)));
      if (angle > min_deg) total += glm::length(m.position(m.vertex(e, 0)) - m.position(m.vertex(e, 1)));
    }
    return total;
  };
  const double before = sharp_length(60);
  deform::HandleTransform twist;
  twist.rotation = glm::angleAxis(glm::radians(180.0), Vec3(0, 0, 1));
  // Handle = the top end; ROI reaches down to the bottom end (held by the fixed rings).
  s.grab_begin(Point(0, 0, 1.0), 0.3, 2.2);
  const int n = 60;
  for (int i = 1; i <= n; ++i) {
    deform::HandleTransform t;
    t.rotation = glm::angleAxis(glm::radians(180.0 * i / n), Vec3(0, 0, 1));
    s.grab_drag(t);
  }
  s.grab_end();
  s.mesh().validate();
  const double after = sharp_length(50);
  const geometry::QualityReport q = s.quality();
  std::printf("bar: sharp edge length %.3f -> %.3f, min angle %.1f, mean min angle %.1f\n", before, after,
              q.min_angle_deg, q.mean_min_angle_deg);
  EXPECT_EQ(q.genus, 0);
  EXPECT_GT(after, 0.85 * before);  // the edges followed the twist and stayed sharp
}

TEST(SculptSession, ThousandRandomGrabsWithUndoRedo) {
  sculpt::Session s;
  s.load(mesh::make_icosphere(2));
  // Coarse sizing keeps the mesh small (a few hundred vertices) whatever the random edits do.
  s.set_settings({{"epsilon", "1%"}, {"min_length", "6%"}, {"max_length", "15%"}});
  std::mt19937 rng(1234);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<mesh::SurfaceMesh> states{s.mesh()};  // states[k] = after k live steps
  size_t position = 0;
  int grabs = 0;
  const int operations = test::operations_for_this_build(1000);  // Release: 1,000
  for (int i = 0; i < operations; ++i) {
    const double r = (u(rng) + 1) / 2;
    if (r < 0.2 && s.can_undo()) {
      ASSERT_TRUE(s.undo());
      --position;
      ASSERT_TRUE(same_mesh(s.mesh(), states[position])) << "undo at op " << i;
    } else if (r < 0.3 && s.can_redo()) {
      ASSERT_TRUE(s.redo());
      ++position;
      ASSERT_TRUE(same_mesh(s.mesh(), states[position])) << "redo at op " << i;
    } else {
      const Point c = glm::normalize(Vec3(u(rng), u(rng), u(rng)) + Vec3(1e-3));
      deform::HandleTransform t;
      t.translation = 0.15 * Vec3(u(rng), u(rng), u(rng));
      t.rotation = glm::angleAxis(0.5 * u(rng), glm::normalize(Vec3(u(rng), u(rng), u(rng)) + Vec3(1e-3)));
      t.scale = 1 + 0.15 * u(rng);
      drag(s, c, 0.3 * (u(rng) + 1) / 2, 0.2 + 0.6 * (u(rng) + 1) / 2, t, 1 + i % 3);
      ++grabs;
      s.mesh().validate();
      states.resize(position + 1);
      // The history is bounded: the oldest steps may have been dropped.
      states.push_back(s.mesh());
      ++position;
    }
  }
  EXPECT_GT(grabs, operations * 6 / 10);
}

TEST(SculptSession, ReplayReport) {
  sculpt::Session s;
  s.load(mesh::make_icosphere(3));
  const nlohmann::json file = nlohmann::json::parse(R"({"version": 1, "settings": {"epsilon": "0.1%"},
    "steps": [{"grab": {"center": [0, 0, 1.2], "handle_radius": 0.1, "roi_radius": 0.6, "translate": [0, 0, 0.5],
               "substeps": 10}},
              {"grab": {"center": [1, 0, 0], "handle_radius": 0.1, "roi_radius": 0.5,
               "rotate": {"axis": [1, 0, 0], "degrees": 40}, "substeps": 4}},
              {"undo": 1}, {"redo": 1}, {"undo": 2}]})");
  const mesh::SurfaceMesh input = s.mesh();
  const nlohmann::json r = s.replay(file);
  EXPECT_EQ(r["frames"], 14);
  for (const char* k : {"frame_ms_median", "frame_ms_p95", "frame_ms_max", "roi_ms_median", "field_ms_median",
                        "refine_ms_median", "deform_ms_median", "remesh_ms_median", "vertices", "faces",
                        "min_angle_deg", "mean_min_angle_deg"})
    EXPECT_TRUE(r.contains(k)) << k;
  EXPECT_TRUE(same_mesh(s.mesh(), input));  // two grabs, undone
  EXPECT_THROW(s.replay(nlohmann::json::parse(R"({"version": 1, "steps": [{"undo": 0}]})")), std::invalid_argument);
}
