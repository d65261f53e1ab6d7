// The biharmonic blending field and the blended handle transform.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "deform/handle_deformer.h"
#include "mesh/primitives.h"
#include "geometry_test_util.h"

using namespace adasculpt;
using mesh::Vertex;
using test::highest_point;

TEST(DeformField, OneOnHandleZeroOutsideMonotoneBetween) {
  const mesh::SurfaceMesh m = mesh::make_icosphere(4);
  deform::HandleDeformer d;
  d.begin(m, highest_point(m), 0.15, 0.9);
  d.compute_region_and_field(m);
  ASSERT_GT(d.handle_vertices().size(), 3u);
  ASSERT_GT(d.free_vertices().size(), 200u);
  for (Vertex v : d.handle_vertices()) EXPECT_EQ(d.field(v), 1.0);
  for (Vertex v : d.fixed_vertices()) EXPECT_EQ(d.field(v), 0.0);
  // Monotone in the mean: averages over distance bands decrease from the handle outwards.
  const int bands = 6;
  std::vector<double> sum(bands, 0), count(bands, 0);
  double max_jump = 0;
  for (Vertex v : d.free_vertices()) {
    const double w = d.field(v);
    EXPECT_GE(w, 0.0);
    EXPECT_LE(w, 1.0);
    const double t = (d.distances().distance(v) - 0.15) / (0.9 - 0.15);
    const int b = std::min(bands - 1, std::max(0, int(t * bands)));
    sum[b] += w;
    count[b] += 1;
    for (Vertex u : m.vertices(v)) max_jump = std::max(max_jump, std::abs(d.field(u) - w));
  }
  for (int b = 1; b < bands; ++b) EXPECT_LT(sum[b] / count[b], sum[b - 1] / count[b - 1]) << "band " << b;
  EXPECT_LT(max_jump, 0.15);  // smooth: no jump between neighbours
  // Rotationally symmetric around the pole: same band, similar values.
  EXPECT_GT(d.last().field_stats.relative_residual, -1.0);
}

TEST(DeformField, PureTranslationWithoutFreeRegionMovesTheHandleRigidly) {
  mesh::SurfaceMesh m = mesh::make_icosphere(3);
  const mesh::SurfaceMesh before = m;
  deform::HandleDeformer d;
  d.begin(m, highest_point(m), 0.3, 0.3);
  deform::HandleTransform t;
  t.translation = Vec3(0.05, -0.02, 0.1);
  auto& r = d.step(m, t, 1e-3);
  EXPECT_EQ(r.n_free, 0u);
  EXPECT_EQ(r.splits, 0u);
  size_t moved = 0;
  for (Vertex v : before.vertices()) {
    const Vec3 delta = m.position(v) - before.position(v);
    if (d.field(v) == 1.0) {
      EXPECT_NEAR(glm::length(delta - t.translation), 0.0, 1e-15);
      ++moved;
    } else {
      EXPECT_EQ(delta, Vec3(0.0));
    }
  }
  EXPECT_EQ(moved, r.n_handle);
  EXPECT_EQ(glm::length(d.center() - (highest_point(before) + t.translation)), 0.0);
}

TEST(DeformField, TranslationWithTinyRoiIsRigidOnTheHandle) {
  mesh::SurfaceMesh m = mesh::make_icosphere(4);
  const mesh::SurfaceMesh before = m;
  deform::HandleDeformer d;
  d.begin(m, highest_point(m), 0.2, 0.25);
  deform::HandleTransform t;
  t.translation = Vec3(0, 0, 0.02);
  d.step(m, t, 1.0);  // epsilon huge: no refinement
  for (Vertex v : d.handle_vertices()) EXPECT_NEAR(glm::length(m.position(v) - before.position(v) - t.translation), 0, 1e-15);
  m.validate();
}

TEST(DeformField, IncrementsComposeToTheTotalOnTheHandle) {
  mesh::SurfaceMesh m = mesh::make_icosphere(3);
  const mesh::SurfaceMesh before = m;
  deform::HandleDeformer d;
  const Point c = highest_point(m);
  d.begin(m, c, 0.25, 0.25);  // handle only: w = 1, rigid
  deform::HandleTransform total;
  const int n = 7;
  for (int i = 1; i <= n; ++i) {
    const double f = double(i) / n;
    total.translation = f * Vec3(0.1, 0.2, 0.3);
    total.rotation = glm::angleAxis(f * 2.5, glm::normalize(Vec3(1, 2, 0.5)));
    total.scale = 1 + f * 0.5;
    d.step(m, total, 0);
  }
  for (Vertex v : d.handle_vertices())
    EXPECT_NEAR(glm::length(m.position(v) - deform::apply(total, c, before.position(v))), 0, 1e-12);
}

TEST(DeformField, RefinementSplitsOnlyWhereTheDeformationBends) {
  mesh::SurfaceMesh m = mesh::make_icosphere(3);
  deform::HandleDeformer d;
  d.begin(m, highest_point(m), 0.2, 1.0);
  deform::HandleTransform t;
  t.translation = Vec3(0, 0, 0.5);
  const size_t nv = m.n_vertices();
  auto& r = d.step(m, t, 1e-3);
  EXPECT_GT(r.splits, 0u);
  EXPECT_EQ(m.n_vertices(), nv + r.splits);
  m.validate();
  // With a huge epsilon nothing is split.
  deform::HandleDeformer d2;
  mesh::SurfaceMesh m2 = mesh::make_icosphere(3);
  d2.begin(m2, highest_point(m2), 0.2, 1.0);
  EXPECT_EQ(d2.step(m2, t, 10.0).splits, 0u);
}

TEST(DeformField, CarriedFactorizationMatchesAFullSolve) {
  // Same topology, slightly deformed geometry: the old factors + iterative refinement.
  mesh::SurfaceMesh m = mesh::make_icosphere(4);
  deform::DeformOptions carry;
  carry.reuse = deform::FieldReuse::CarryFactorization;
  deform::HandleDeformer a(carry), b;
  const Point c = highest_point(m);
  a.begin(m, c, 0.15, 0.8);
  b.begin(m, c, 0.15, 0.8);
  a.compute_region_and_field(m);
  b.compute_region_and_field(m);
  for (Vertex v : m.vertices()) m.position(v) *= 1.0 + 0.01 * m.position(v).x;  // small smooth change
  a.recompute_field(m);
  b.recompute_field(m);
  ASSERT_EQ(a.free_vertices().size(), b.free_vertices().size());
  EXPECT_FALSE(a.last().field_stats.factorized);
  double err = 0;
  for (Vertex v : b.free_vertices()) err = std::max(err, std::abs(a.field(v) - b.field(v)));
  std::printf("carried factorisation: max field error %.2e after %d refinement steps\n", err,
              a.last().field_stats.refinement_steps);
  EXPECT_LT(err, 1e-4);
}
