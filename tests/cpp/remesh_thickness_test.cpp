// Thin parts (cpp/remesh/thickness.cpp): a plate far thinner than the edges the tolerance asks
// for is sized by its thickness and kept, not crumpled: the remeshed plate stays within 2 epsilon
// of the input. Without the clamp (edges of the max length across a 0.01 rim) the rim folded
// in: Hausdorff 1.25 / 7.5 / 16.3 % of the diagonal at epsilon 0.5 / 2 / 5 %.
#include <gtest/gtest.h>

#include <vector>

#include "geometry/quality.h"
#include "geometry/topology.h"
#include "mesh/primitives.h"
#include "remesh/remesher.h"
#include "test_build.h"

using namespace adasculpt;
using mesh::SurfaceMesh;

namespace {

constexpr double kThickness = 0.01;

// 1 x 1 x 0.01, every face a grid of squares 0.025 wide: fine enough for the clamp at each vertex
// to stay near the rim it was measured at.
SurfaceMesh thin_plate() { return mesh::make_box(40, 40, 1, 1.0, 1.0, kThickness); }

remesh::RemeshOptions adaptive(const SurfaceMesh& m, double eps_pct, double min_pct) {
  const double d = remesh::bounding_box_diagonal(m);
  remesh::RemeshOptions o = remesh::default_options_for(m);
  o.epsilon = eps_pct * 0.01 * d;
  o.min_length = min_pct * 0.01 * d;
  o.iterations = 3;
  return o;
}

}  // namespace

TEST(RemeshThickness, ThinPlateStaysWithinTwiceEpsilon) {
  if (test::kSanitizedBuild) GTEST_SKIP() << "a quality figure over several whole remeshes, minutes under ASan: the Release ctest runs it";
  const SurfaceMesh input = thin_plate();
  for (double eps_pct : {0.5, 2.0}) {
    SurfaceMesh m = input;
    const remesh::RemeshReport report = remesh::remesh(m, adaptive(input, eps_pct, 0.2));
    ASSERT_NO_THROW(m.validate());
    EXPECT_TRUE(report.warning.empty()) << report.warning;
    EXPECT_EQ(geometry::components(m), 1);
    EXPECT_EQ(geometry::genus(m), 0);
    const geometry::DistanceReport d = geometry::distance_between(m, input, 20000);
    EXPECT_LE(100 * d.hausdorff_rel, 2 * eps_pct) << "epsilon " << eps_pct << " %";
    // Sized by the thickness, not down to nothing: edges about as long as the plate is thick.
    const geometry::QualityReport q = geometry::quality_report(m);
    EXPECT_GT(q.edge_length_mean, 0.5 * kThickness);
    EXPECT_GE(q.min_angle_deg, 20.0);
  }
}

// The clamp depends on the plate, not on the tolerance, and which vertices it clamps not on the
// min length (its floor, a fraction of the min length, only grows with it): coarser settings
// never ask for more vertices on the plate.
TEST(RemeshThickness, CoarserSettingsGiveNoMoreVerticesOnAThinPlate) {
  if (test::kSanitizedBuild) GTEST_SKIP() << "a quality figure over several whole remeshes, minutes under ASan: the Release ctest runs it";
  const SurfaceMesh input = thin_plate();
  auto count = [&](double eps_pct, double min_pct) {
    SurfaceMesh m = input;
    remesh::remesh(m, adaptive(input, eps_pct, min_pct));
    EXPECT_NO_THROW(m.validate());
    return double(m.n_vertices());
  };
  // A few vertices either way between settings whose fields agree almost everywhere (the budget
  // tests allow 3 % + 5 for the same reason).
  auto expect_non_increasing = [](const std::vector<double>& counts, const char* what) {
    for (size_t i = 1; i < counts.size(); ++i)
      EXPECT_LE(counts[i], 1.03 * counts[i - 1] + 5) << what << " step " << i;
  };
  expect_non_increasing({count(0.5, 0.2), count(2.0, 0.2), count(5.0, 0.2)}, "epsilon");
  expect_non_increasing({count(2.0, 0.05), count(2.0, 0.2), count(2.0, 1.0)}, "min length");
}
