// The structures that follow a changing mesh from the session's reported changes, as Session feeds
// them: FaceSlotTree (geometry/face_slot_tree.h) and AngleFigures (geometry/angle_figures.h). On a
// mesh that strokes, grabs, undos and redos keep changing, the tree's rays and closest points equal
// those of a TriangleTree built from scratch (an independent exact search) after every operation,
// Session::pick agrees with it, and Session::quick_quality equals a whole quality_report; and the
// work after a stroke follows the stroke, not the mesh.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include <glm/geometric.hpp>

#include "geometry/aabb_tree.h"
#include "geometry/angle_figures.h"
#include "geometry/face_slot_tree.h"
#include "geometry/quality.h"
#include "mesh/primitives.h"
#include "sculpt/session.h"
#include "sculpt_test_util.h"

using namespace adasculpt;

namespace {

// What the Session does with its changes: mark, then forget them.
template <class Follower>
void feed(sculpt::Session& s, Follower& follower) {
  for (mesh::Vertex v : s.changes().touched_vertices) follower.mark_vertex(s.mesh(), v);
  for (mesh::Face f : s.changes().touched_faces) follower.mark_face(f);
  s.clear_changes();
}

// Session::quick_quality against the whole report.
void expect_quick_quality_right(const sculpt::Session& s, const std::string& at) {
  const geometry::QualityReport quick = s.quick_quality(), full = geometry::quality_report(s.mesh());
  ASSERT_EQ(quick.vertices, full.vertices) << at;
  ASSERT_EQ(quick.faces, full.faces) << at;
  ASSERT_EQ(quick.edges, full.edges) << at;
  ASSERT_EQ(quick.min_angle_deg, full.min_angle_deg) << at;
  ASSERT_EQ(quick.max_angle_deg, full.max_angle_deg) << at;
  ASSERT_NEAR(quick.mean_min_angle_deg, full.mean_min_angle_deg, 1e-9) << at;
  ASSERT_EQ(quick.pct_min_angle_lt_30, full.pct_min_angle_lt_30) << at;
  ASSERT_EQ(quick.pct_min_angle_lt_10, full.pct_min_angle_lt_10) << at;
}

sculpt::BrushStroke stroke(const Vec3& dir, const Vec3& along, deform::BrushTool tool, double radius) {
  sculpt::BrushStroke st;
  st.settings.tool = tool;
  st.settings.radius = radius;
  st.settings.strength = 0.7;
  for (int i = 0; i < 6; ++i) st.path.push_back(Point(glm::normalize(dir + (0.07 * i) * along)));
  return st;
}

struct Rng {
  std::mt19937 gen{11};
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(gen); }
  Vec3 direction() {
    const Vec3 d(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    return glm::dot(d, d) < 1e-6 ? Vec3(0, 0, 1) : glm::normalize(d);
  }
};

// Rays from outside towards the sphere, every 5th along an axis; points near and off the surface.
void expect_same_answers(const mesh::SurfaceMesh& m, geometry::FaceSlotTree& tree, Rng& rng, const std::string& at) {
  tree.sync(m);
  geometry::TriangleTree oracle;
  oracle.build(m);
  for (int i = 0; i < 60; ++i) {
    Point origin = Point(2.5 * rng.direction());
    Vec3 dir = glm::normalize(Point(0.8 * rng.direction()) - origin);
    if (i % 5 == 0) origin.z = 3, dir = Vec3(0, 0, -1);
    const auto want = oracle.intersect_ray(origin, dir);
    const auto got = tree.intersect_ray(m, origin, dir);
    ASSERT_EQ(got.face.is_valid(), want.hit) << at << ", ray " << i;
    if (want.hit) {
      ASSERT_EQ(got.t, want.t) << at << ", ray " << i;
      ASSERT_EQ(got.point, want.point) << at << ", ray " << i;
    }
    const Point q = Point(rng.uniform(0.2, 1.6) * rng.direction());
    const auto near = tree.closest_point(m, q);
    ASSERT_TRUE(near.face.is_valid()) << at;
    ASSERT_EQ(near.distance2, oracle.closest_point(q).distance2) << at << ", point " << i;
  }
}

}  // namespace

TEST(FaceSlotTree, FollowsStrokesGrabsUndosAndRedosExactly) {
  sculpt::Session s;
  s.load(mesh::make_icosphere(3));
  s.set_settings({{"epsilon", "0.2%"}, {"min_length", "2%"}, {"max_length", "6%"}});  // split and collapse
  geometry::FaceSlotTree tree;
  Rng rng;
  expect_quick_quality_right(s, "loaded");
  s.clear_changes();
  expect_same_answers(s.mesh(), tree, rng, "loaded");
  int refits_below_all = 0;
  for (int op = 0; op < 60; ++op) {
    const std::string at = "operation " + std::to_string(op);
    const int kind = int(rng.gen() % 10);
    if (kind < 5) {
      s.brush_stroke(stroke(rng.direction(), rng.direction(), deform::BrushTool(rng.gen() % 7), rng.uniform(0.15, 0.4)));
    } else if (kind < 7) {
      s.grab_begin(Point(rng.direction()), 0.05, rng.uniform(0.2, 0.6));
      deform::HandleTransform t;
      t.translation = 0.2 * rng.direction();
      s.grab_drag(t);
      feed(s, tree);  // a frame in between, as the viewer clears the changes every frame
      t.translation *= 1.5;
      s.grab_drag(t);
      s.grab_end();
    } else if (kind < 9) {
      s.undo();
    } else {
      s.redo();
    }
    // Read with the changes still listed (the app's 'end' event) or after they were cleared.
    if (op % 2 == 0) expect_quick_quality_right(s, at);
    feed(s, tree);
    if (op % 2 == 1) expect_quick_quality_right(s, at);
    expect_same_answers(s.mesh(), tree, rng, at);
    if (HasFatalFailure()) return;
    // Session::pick answers from its own tree, fed the same way.
    const Point origin = Point(2.5 * rng.direction());
    const Vec3 dir = glm::normalize(-Vec3(origin));
    Point picked;
    const auto want = tree.intersect_ray(s.mesh(), origin, dir);
    ASSERT_EQ(s.pick(origin, dir, &picked), want.face.is_valid()) << at;
    if (want.face.is_valid()) {
      ASSERT_EQ(picked, want.point) << at;
    }
    refits_below_all += tree.last_refit() > 0;
  }
  s.mesh().validate();
  EXPECT_GT(refits_below_all, 30);  // the refits ran, not only whole builds
}

// Both followers at once (feed clears the changes after marking).
struct Followers {
  geometry::FaceSlotTree tree;
  geometry::AngleFigures figures;
  void mark_vertex(const mesh::SurfaceMesh& m, mesh::Vertex v) {
    tree.mark_vertex(m, v);
    figures.mark_vertex(m, v);
  }
  void mark_face(mesh::Face f) {
    tree.mark_face(f);
    figures.mark_face(f);
  }
};

// The same stroke on the first of 1 or 16 sphere copies: the tree refits about as many leaves and
// the angle figures recompute about as many faces after it on 16 copies as on one, far fewer than
// the scene holds; and the figures are the whole report's.
TEST(FaceSlotTree, WorkAfterAStrokeFollowsTheStrokeNotTheMesh) {
  size_t refit[2] = {0, 0}, recomputed[2] = {0, 0}, faces[2] = {0, 0};
  const int copies[2] = {1, 16};
  for (int i = 0; i < 2; ++i) {
    sculpt::Session s;
    s.load(test::sphere_copies(copies[i]));
    s.set_settings({{"min_length", "1%"}, {"max_length", "2%"}});
    Followers f;
    s.clear_changes();
    f.tree.sync(s.mesh());
    f.figures.sync(s.mesh());
    faces[i] = s.mesh().faces_size();
    EXPECT_EQ(f.figures.last_work(), faces[i]) << "the first sync computes every face";
    s.brush_stroke(stroke(Vec3(0, 0, 1), Vec3(0, 1, 0), deform::BrushTool::Draw, 0.3));
    feed(s, f);
    f.tree.sync(s.mesh());
    f.figures.sync(s.mesh());
    refit[i] = f.tree.last_refit();
    recomputed[i] = f.figures.last_work();
    Point hit;
    ASSERT_TRUE(s.pick(Point(0, 0, 3), Vec3(0, 0, -1), &hit));
    EXPECT_EQ(hit, f.tree.intersect_ray(s.mesh(), Point(0, 0, 3), Vec3(0, 0, -1)).point);
    geometry::QualityReport r;
    f.figures.fill(r);
    EXPECT_EQ(r.min_angle_deg, geometry::quality_report(s.mesh()).min_angle_deg);
  }
  EXPECT_GT(refit[0], 0u);
  EXPECT_LT(refit[1], 2 * refit[0] + 8);
  EXPECT_LT(refit[1] * 16, faces[1] / 8);  // leaves of 16 slots: well under an eighth of the scene
  EXPECT_GT(recomputed[0], 0u);
  EXPECT_LT(recomputed[1], 2 * recomputed[0] + 16);
  EXPECT_LT(recomputed[1], faces[1] / 8);
}
