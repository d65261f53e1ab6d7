// The budgets of a grab frame (issue 18, the frame-time tail): the frame plan gives the field's
// solve what the region's work leaves of the frame (sculpt/grab.h), the region iteration collapses
// at most its share of the scope per frame (the leftovers are done by later frames), and a pull
// under both budgets still ends on a valid mesh with good angles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "geometry/quality.h"
#include "geometry/triangle.h"
#include "mesh/primitives.h"
#include "geometry_test_util.h"
#include "remesh/remesher.h"
#include "sculpt/grab.h"

using namespace adasculpt;
using mesh::Vertex;
using test::highest_point;

namespace {

// A grab driven the way the session drives it, on its own remesher.
struct GrabRig {
  mesh::SurfaceMesh mesh;
  remesh::RemeshOptions options;
  std::unique_ptr<remesh::Remesher> remesher;
  sculpt::Grab grab;
  sculpt::FrameTimings timings;
  sculpt::ChangeSet changes;

  explicit GrabRig(mesh::SurfaceMesh m, double min_length_scale = 1.0, double epsilon_scale = 1.0)
      : mesh(std::move(m)) {
    options = remesh::default_options_for(mesh);
    options.min_length *= min_length_scale;
    options.epsilon *= epsilon_scale;
    options.max_length = std::max(options.max_length, options.min_length);
    remesher = std::make_unique<remesh::Remesher>(mesh, options);
  }
  void begin(double handle_radius, double roi_radius) {
    const Point top = highest_point(mesh);
    mesh::Vertex near;
    double best = 1e300;
    for (Vertex v : mesh.vertices()) {
      const double d = glm::length(mesh.position(v) - top);
      if (d < best) best = d, near = v;
    }
    mesh::Face face;
    for (mesh::Face f : mesh.faces(near)) face = f;
    grab.begin(mesh, top, face, handle_radius, roi_radius);
  }
  void drag(const Vec3& translation) {
    deform::HandleTransform t;
    t.translation = translation;
    grab.drag(mesh, *remesher, t, options.epsilon, timings, changes);
  }
};

// The smallest angle of the triangles with a corner in `region`, in degrees.
double region_min_angle_deg(const mesh::SurfaceMesh& m, const std::vector<Vertex>& region) {
  double worst = 180;
  for (Vertex v : region) {
    if (m.is_deleted(v)) continue;
    for (mesh::Face f : m.faces(v)) {
      Vertex c[3];
      m.face_vertices(f, c);
      double angles[3];
      geometry::triangle_angles(m.position(c[0]), m.position(c[1]), m.position(c[2]), angles);
      worst = std::min(worst, *std::min_element(angles, angles + 3) * 180.0 / M_PI);
    }
  }
  return worst;
}

TEST(GrabFramePlan, TheFieldGetsWhatTheRegionLeavesOfTheFrame) {
  deform::DeformOptions o;
  o.frame_work = 5e6;
  using P = sculpt::FramePlan;
  const sculpt::FramePlan light = sculpt::plan_frame(5000, false, o);
  EXPECT_DOUBLE_EQ(light.region_work, 5000 * P::kRegionWorkPerVertex);
  EXPECT_DOUBLE_EQ(light.field.work + light.region_work, o.frame_work);
  EXPECT_FALSE(light.field.defer_large_steps);
  const sculpt::FramePlan sizing = sculpt::plan_frame(5000, true, o);
  EXPECT_DOUBLE_EQ(sizing.region_work, 5000 * (P::kRegionWorkPerVertex + P::kSizingWorkPerVertex));
  EXPECT_DOUBLE_EQ(sizing.field.work + sizing.region_work, o.frame_work);
  EXPECT_TRUE(sizing.field.defer_large_steps);
  // A region whose own work passes the frame leaves the field its minimum share, not nothing:
  // the solve always advances.
  const sculpt::FramePlan huge = sculpt::plan_frame(100000, true, o);
  EXPECT_DOUBLE_EQ(huge.field.work, P::kMinFieldFraction * o.frame_work);
  // Such a frame leaves the field's one-piece steps to a lighter one, sizing or not.
  EXPECT_TRUE(sculpt::plan_frame(100000, false, o).field.defer_large_steps);
}

// A resting grab on a fine sphere whose settings ask for edges 4x longer: the region wants to lose
// most of its vertices. No frame collapses more than an eighth of its scope; later frames finish
// the work (the collapses die down and the region ends coarse).
TEST(GrabFramePlan, CollapsesStayWithinTheirShareAndTheLeftoversAreDone) {
  GrabRig rig(mesh::make_icosphere(5), 4.0);
  rig.begin(0.1, 0.8);
  size_t first_region = 0, capped_frames = 0, last_collapses = 0;
  for (int i = 1; i <= 40; ++i) {
    const size_t before = rig.grab.deformer().last().region.size();
    if (i == 1) first_region = before;
    rig.drag(Vec3(0.0));
    const sculpt::FrameTimings& f = rig.timings;
    // The iteration's scope (the part of the region it remeshed, sculpt/region_strain.h) as it
    // was before the iteration, and at most that plus the vertices the iteration added.
    const size_t scope_before = size_t(f.remeshed_vertices) + size_t(f.collapses) - size_t(f.splits);
    const size_t scope = scope_before + size_t(f.splits);
    ASSERT_LE(f.remeshed_vertices, int(before + size_t(f.refine_splits) + size_t(f.splits))) << "frame " << i;
    ASSERT_LE(size_t(f.collapses), scope / 8 + 1) << "frame " << i;
    if (size_t(f.collapses) + 2 >= scope_before / 8) ++capped_frames;
    last_collapses = size_t(f.collapses);
  }
  rig.grab.end(rig.mesh, *rig.remesher, rig.changes);
  rig.mesh.validate();
  EXPECT_GE(capped_frames, 2u) << "the share never bound: the test does not exercise it";
  EXPECT_LE(last_collapses, first_region / 100) << "the leftovers were not done";
  EXPECT_LT(rig.grab.deformer().last().region.size(), first_region / 2);
}

// A pull with a small frame budget, so that the plan binds: in the frames that measure the sizing
// again, the field does no more than its share (plus at most one row of the factorisation), the
// solve still finishes several times, and the pulled mesh keeps its angles.
TEST(GrabFramePlan, PullFramesKeepTheirFieldShareAndTheMeshItsQuality) {
  GrabRig rig(mesh::make_icosphere(5));
  rig.grab.options().frame_work = 1e6;
  rig.begin(0.1, 0.8);
  const double row_slack = 5e4;
  int deferring_frames = 0, refreshes = 0;
  for (int i = 1; i <= 60; ++i) {
    rig.drag(Vec3(0, 0, 0.5 * i / 60.0));
    const sculpt::FramePlan& plan = rig.grab.last_plan();
    const deform::StepResult& r = rig.grab.deformer().last();
    if (plan.field.defer_large_steps) {
      ++deferring_frames;
      EXPECT_LE(r.field_work, plan.field.work + row_slack) << "frame " << i;
    }
    refreshes = r.field_refreshes;
    rig.mesh.validate();
  }
  const std::vector<Vertex> region = rig.grab.deformer().last().region;
  rig.grab.end(rig.mesh, *rig.remesher, rig.changes);
  EXPECT_GE(deferring_frames, 10);
  EXPECT_GE(refreshes, 2) << "the field's solve stalled under the plan";
  EXPECT_GT(region_min_angle_deg(rig.mesh, region), 20.0);
  const geometry::QualityReport q = geometry::quality_report(rig.mesh);
  EXPECT_GT(q.min_angle_deg, 15.0);
  EXPECT_LT(q.pct_min_angle_lt_30, 2.0);
}

// A grab frame that remeshes more than the remesher's spreading size measures a slice of its
// sizing, never the whole scope at once after the first frame (which measures the new vertices of
// a fresh remesher): no such frame is followed by a heavier sizing frame, and the mesh keeps its
// angles.
TEST(GrabFramePlan, ALargeRegionMeasuresItsSizingASliceAtATime) {
  // epsilon at 1/25 of the default: the sphere's sizing is about its edge length (no coarsening).
  GrabRig rig(mesh::make_icosphere(6), 1.0, 0.04);
  rig.begin(0.1, 0.8);
  int large_frames = 0;
  bool last_was_large = false;
  double last_remeshed = 0;
  for (int i = 1; i <= 30; ++i) {
    rig.drag(Vec3(0, 0, 0.4 * i / 30.0));
    // (a frame's remeshing scope may be smaller: only what the pull strained, sculpt/region_strain.h)
    const bool large = rig.timings.remeshed_vertices >= 4096;
    if (large) {
      ++large_frames;
      EXPECT_FALSE(rig.remesher->sizing_due()) << "frame " << i;
    }
    // The frame after a large one planned no sizing measurement.
    if (i > 1 && last_was_large) {
      EXPECT_DOUBLE_EQ(rig.grab.last_plan().region_work, last_remeshed * sculpt::FramePlan::kRegionWorkPerVertex)
          << "frame " << i;
    }
    last_was_large = large;
    last_remeshed = rig.timings.remeshed_vertices;
  }
  const std::vector<Vertex> region = rig.grab.deformer().last().region;
  rig.grab.end(rig.mesh, *rig.remesher, rig.changes);
  rig.mesh.validate();
  EXPECT_GE(large_frames, 10) << "the scopes are too small to exercise the spreading";
  EXPECT_GT(region_min_angle_deg(rig.mesh, region), 20.0);
  EXPECT_LT(geometry::quality_report(rig.mesh).pct_min_angle_lt_30, 2.0);
}

}  // namespace
