// The carried field of a grab (issue 18): the amortised exact solve, the field carried through
// remeshing, the ROI's vertex budget, and the carried pull against the paper's every-frame solve.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "deform/biharmonic_solver.h"
#include "deform/geodesic.h"
#include "deform/handle_deformer.h"
#include "geometry/aabb_tree.h"
#include "mesh/primitives.h"
#include "geometry_test_util.h"
#include "sculpt/session.h"

using namespace adasculpt;
using mesh::Vertex;
using test::highest_point;

namespace {


// A bi-Laplacian system of an n x n grid (uniform 5-point rows, w = 1 on the left column's
// neighbours, 0 elsewhere outside): rows over the whole (n+2)^2 grid, columns the inner n^2.
deform::BiharmonicSystem grid_system(int n) {
  const int side = n + 2;
  auto col = [&](int i, int j) { return (i >= 1 && i <= n && j >= 1 && j <= n) ? (i - 1) * n + (j - 1) : -1; };
  deform::BiharmonicSystem s;
  s.clear(n * n, side * side);
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      const int r = i * side + j;
      double g = 0;
      const int di[5] = {0, 1, -1, 0, 0}, dj[5] = {0, 0, 0, 1, -1};
      for (int k = 0; k < 5; ++k) {
        const int ii = i + di[k], jj = j + dj[k];
        const double w = k == 0 ? -4.0 : 1.0;
        const int c = col(ii, jj);
        if (c >= 0)
          s.add(r, c, w);
        else if (jj == 0 && ii >= 0 && ii < side)
          g += w;  // the "handle" column
      }
      s.inv_mass[r] = 1.0 / (1.0 + 0.01 * r);
      s.known_rhs[r] = g;
    }
  return s;
}

}  // namespace

TEST(DeformCarriedField, AmortisedSolveEqualsTheDirectSolveOverManyCalls) {
  const deform::BiharmonicSystem s = grid_system(24);
  deform::BiharmonicSolver direct, amortised;
  std::vector<double> x, lap;
  direct.solve(s, x, deform::FieldReuse::Exact, 0, 0, &lap);
  amortised.begin_amortized(s);
  int calls = 1;
  while (!amortised.advance_amortized(0.0)) ++calls;  // zero budget: one step per call
  EXPECT_GT(calls, 4);  // assembly, ordering, analysis, several row batches, solve
  EXPECT_FALSE(amortised.amortized_running());
  ASSERT_EQ(amortised.amortized_solution().size(), x.size());
  double err = 0, lap_err = 0;
  for (size_t i = 0; i < x.size(); ++i) err = std::max(err, std::abs(x[i] - amortised.amortized_solution()[i]));
  for (size_t r = 0; r < lap.size(); ++r) lap_err = std::max(lap_err, std::abs(lap[r] - amortised.amortized_laplacian()[r]));
  EXPECT_LT(err, 1e-10);
  EXPECT_LT(lap_err, 1e-8);
  EXPECT_GT(*std::max_element(x.begin(), x.end()), 0.1);  // a real solution, not zeros
}

TEST(DeformCarriedField, ARestingGrabConvergesToTheFullSolve) {
  mesh::SurfaceMesh m = mesh::make_icosphere(4);
  deform::HandleDeformer d;  // carried by default
  ASSERT_EQ(d.options().field_solve, deform::FieldSolve::Carried);
  d.options().field_work_per_frame = 2e5;  // the exact solve spread over several frames
  d.begin(m, highest_point(m), 0.15, 0.9);
  const deform::HandleTransform identity;
  d.step(m, identity, 1e-3);
  // The first frame's field is the radial profile: close, not exact.
  const double first = d.field_error_vs_full_solve(m);
  EXPECT_GT(first, 1e-6);
  EXPECT_LT(first, 0.2);
  int frames = 1;
  while (d.last().field_refreshes == 0 && frames < 200) {
    d.step(m, identity, 1e-3);
    ++frames;
  }
  ASSERT_GT(d.last().field_refreshes, 0) << "no exact solve finished in 200 frames";
  EXPECT_LT(d.field_error_vs_full_solve(m), 1e-9);  // nothing moved: the solve is current
  for (Vertex v : d.handle_vertices()) EXPECT_EQ(d.field(v), 1.0);
  for (Vertex v : d.free_vertices()) {
    EXPECT_GE(d.field(v), 0.0);
    EXPECT_LE(d.field(v), 1.0);
  }
}

TEST(DeformCarriedField, FieldCarriedThroughRemeshingStaysValid) {
  sculpt::Session s;
  s.load(mesh::make_icosphere(4));
  s.grab_begin(highest_point(s.mesh()), 0.15, 0.9);
  for (int i = 1; i <= 30; ++i) {
    deform::HandleTransform t;
    t.translation = Vec3(0, 0, 0.6 * i / 30.0);
    s.grab_drag(t);
    s.mesh().validate();
  }
  s.grab_end();
  s.mesh().validate();
  EXPECT_GT(s.quality().min_angle_deg, 5.0);
}

// The same pull, the paper's way (ROI and field solved every frame) and carried: the two surfaces
// stay within a small fraction of the pull of each other (both ways move the handle rigidly, and
// the ROI of the every-frame solve is the geodesic disc of the stretched surface, so they are not
// identical).
TEST(DeformCarriedField, CarriedPullStaysCloseToTheEveryFrameSolve) {
  const double pull = 0.4;
  auto run = [&](deform::FieldSolve mode) {
    sculpt::Session s;
    s.load(mesh::make_icosphere(4));
    s.grab_options().field_solve = mode;
    s.grab_begin(highest_point(s.mesh()), 0.15, 0.9);
    for (int i = 1; i <= 30; ++i) {
      deform::HandleTransform t;
      t.translation = Vec3(0, 0, pull * i / 30.0);
      s.grab_drag(t);
    }
    s.grab_end();
    s.mesh().validate();
    return s.mesh();
  };
  const mesh::SurfaceMesh every = run(deform::FieldSolve::EveryFrame);
  const mesh::SurfaceMesh carried = run(deform::FieldSolve::Carried);
  geometry::TriangleTree tree;
  tree.build(every);
  double worst = 0, top_z_every = -1e300, top_z_carried = -1e300;
  for (Vertex v : carried.vertices())
    worst = std::max(worst, std::sqrt(tree.closest_point(carried.position(v)).distance2));
  for (Vertex v : every.vertices()) top_z_every = std::max(top_z_every, every.position(v).z);
  for (Vertex v : carried.vertices()) top_z_carried = std::max(top_z_carried, carried.position(v).z);
  RecordProperty("max_distance_over_pull", std::to_string(worst / pull));
  EXPECT_NEAR(top_z_carried, top_z_every, 1e-3);  // the handle goes where the pointer goes
  EXPECT_LT(worst, 0.05 * pull) << "carried surface farther than 5% of the pull from the every-frame one";  // 1.7% measured
}

TEST(DeformCarriedField, RoiIsCutToTheVertexBudgetAndSaysSo) {
  deform::HandleTransform t;
  t.translation = Vec3(0, 0, 0.05);
  {
    sculpt::Session s;
    s.load(mesh::make_icosphere(5));  // 10k vertices
    s.grab_begin(highest_point(s.mesh()), 0.2, 1.2);
    s.grab_drag(t);
    EXPECT_FALSE(s.last_frame().roi_capped);
    EXPECT_GT(s.last_frame().roi_vertices, 1500);
  }
  sculpt::Session s;
  s.load(mesh::make_icosphere(5));
  s.grab_options().max_roi_vertices = 1000;
  s.grab_begin(highest_point(s.mesh()), 0.2, 1.2);
  s.grab_drag(t);
  EXPECT_TRUE(s.last_frame().roi_capped);
  EXPECT_LE(s.last_frame().roi_vertices, 1000 + 50);  // + vertices the first frame's refinement added
  EXPECT_GE(s.last_frame().roi_vertices, 900);
  s.grab_drag(t);  // the flag holds for the whole grab
  EXPECT_TRUE(s.last_frame().roi_capped);
  s.grab_end();
  s.mesh().validate();
}

TEST(DeformCarriedField, GeodesicMarchStopsAtTheVertexBudget) {
  const mesh::SurfaceMesh m = mesh::make_icosphere(4);
  deform::GeodesicWorkspace ws;
  deform::geodesic_distance(m, {{Vertex(0), 0.0}}, 1e300, ws, false, 300);
  ASSERT_EQ(ws.order().size(), 300u);
  for (size_t i = 1; i < ws.order().size(); ++i)
    EXPECT_LE(ws.distance(ws.order()[i - 1]), ws.distance(ws.order()[i]));
  // The 300 nearest: nothing outside the budget is nearer than the last one inside.
  deform::GeodesicWorkspace all;
  deform::geodesic_distance(m, {{Vertex(0), 0.0}}, 1e300, all);
  EXPECT_DOUBLE_EQ(all.distance(all.order()[299]), ws.distance(ws.order()[299]));
}
