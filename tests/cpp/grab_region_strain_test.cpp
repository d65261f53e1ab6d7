// Which part of a grab's region each frame remeshes (sculpt/region_strain.h, issue 18): what the
// deformation strained, what the last iteration left unsettled, and two rings around them; never a
// rigidly moved part; the whole region with threshold 0 (the paper's scheme).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include <glm/geometric.hpp>

#include "geometry/quality.h"
#include "mesh/primitives.h"
#include "sculpt/grab.h"
#include "sculpt/region_strain.h"
#include "sculpt/session.h"
#include "undo_test_util.h"

using namespace adasculpt;
using mesh::Vertex;

namespace {

std::vector<Vertex> all_vertices(const mesh::SurfaceMesh& m) {
  std::vector<Vertex> r;
  for (Vertex v : m.vertices()) r.push_back(v);
  return r;
}

// The vertices within `rings` edges of v.
std::set<mesh::Index> within_rings(const mesh::SurfaceMesh& m, Vertex v, int rings) {
  std::set<mesh::Index> seen{v.idx};
  std::vector<Vertex> front{v};
  for (int r = 0; r < rings; ++r) {
    std::vector<Vertex> next;
    for (Vertex u : front)
      for (Vertex w : m.vertices(u))
        if (seen.insert(w.idx).second) next.push_back(w);
    front.swap(next);
  }
  return seen;
}

// One frame as a grab runs it, without a remesher: select, (no iteration), update.
std::vector<Vertex> frame(sculpt::RegionStrain& strain, const mesh::SurfaceMesh& m, std::vector<Vertex>& region,
                          double threshold) {
  std::vector<Vertex> scope;
  strain.select(m, region, threshold, scope);
  strain.update_region(m, region, scope);
  return scope;
}

std::set<mesh::Index> indices(const std::vector<Vertex>& vertices) {
  std::set<mesh::Index> r;
  for (Vertex v : vertices) r.insert(v.idx);
  return r;
}

// A sphere whose every vertex is the region, after a grab's first frame (which takes them all).
struct SphereAfterFirstFrame {
  mesh::SurfaceMesh m = mesh::make_icosphere(3);
  std::vector<Vertex> region = all_vertices(m);
  sculpt::RegionStrain strain;
  SphereAfterFirstFrame() {
    strain.reset();
    frame(strain, m, region, 0.1);
  }
};

}  // namespace

TEST(RegionStrain, FirstFrameTakesAllThenARigidMotionTakesNothing) {
  mesh::SurfaceMesh m = mesh::make_icosphere(3);
  std::vector<Vertex> region = all_vertices(m);
  sculpt::RegionStrain strain;
  strain.reset();
  EXPECT_EQ(frame(strain, m, region, 0.1).size(), region.size()) << "nothing is known at the first frame";
  for (Point& p : m.positions()) p += Vec3(0.3, -0.2, 0.1);  // a translation of everything
  EXPECT_TRUE(frame(strain, m, region, 0.1).empty());
  // Threshold 0: the whole region every frame, as in the paper.
  for (Point& p : m.positions()) p += Vec3(0.3, -0.2, 0.1);
  EXPECT_EQ(frame(strain, m, region, 0.0).size(), region.size());
}

TEST(RegionStrain, AStrainedVertexTakesItselfAndTwoRingsOnceItsStrainAddsUp) {
  SphereAfterFirstFrame s;
  auto& [m, region, strain] = s;
  const Vertex moved(0);
  double edge = 1e300;
  for (Vertex w : m.vertices(moved)) edge = std::min(edge, glm::length(m.position(w) - m.position(moved)));
  const Vec3 out = glm::normalize(m.position(moved) - Point(0.0));
  // 4 % of the shortest edge per frame: under the threshold of 10 % for two frames, over it at the
  // third (the strain adds up; the vertex's neighbours see the same edge change).
  for (int i = 1; i <= 3; ++i) {
    m.position(moved) += 0.04 * edge * out;
    const std::vector<Vertex> scope = frame(strain, m, region, 0.1);
    if (i < 3) {
      EXPECT_TRUE(scope.empty()) << "frame " << i;
      continue;
    }
    // The moved vertex and its neighbours are strained; the scope adds two rings around them.
    EXPECT_EQ(indices(scope), within_rings(m, moved, 1 + sculpt::RegionStrain::kScopeRings));
  }
  // Strain starts again from 0 for what was taken.
  m.position(moved) += 0.04 * edge * out;
  EXPECT_TRUE(frame(strain, m, region, 0.1).empty());
}

TEST(RegionStrain, ANewVertexTakesItsNeighbourhoodAndAnUndoneGrabLeavesNoTrace) {
  SphereAfterFirstFrame s;
  auto& [m, region, strain] = s;
  // A split (as the refinement makes): the new vertex joins the region.
  const mesh::Edge e = *m.edges().begin();
  const Vertex a = m.vertex(e, 0), b = m.vertex(e, 1);
  const Vertex added = m.split(e, 0.5 * (m.position(a) + m.position(b)));
  region.push_back(added);
  std::vector<Vertex> scope;
  strain.select(m, region, 0.1, scope);
  EXPECT_EQ(indices(scope), within_rings(m, added, 1 + sculpt::RegionStrain::kScopeRings));
  strain.update_region(m, region, scope);
  // A new grab knows nothing of the last one's vertices.
  strain.reset();
  EXPECT_EQ(frame(strain, m, region, 0.1).size(), region.size());
}

// A pull on a session: frames remesh part of the region only, and the mesh keeps its quality as
// well as with the whole region every frame.
TEST(RegionStrain, APullRemeshesWhatItStrainsAndKeepsTheQualityOfTheWholeRegion) {
  auto pull = [](double threshold, double& remeshed_fraction, double& top) {
    sculpt::Session s;
    s.load(mesh::make_icosphere(5));
    s.set_settings({{"epsilon", "0.1%"}, {"min_length", "0.5%"}, {"max_length", "8%"}});
    s.grab_options().remesh_strain = threshold;
    s.grab_begin(Point(0, 0, 1), 0.2, 0.9);
    double remeshed = 0, roi = 0;
    for (int i = 1; i <= 40; ++i) {
      deform::HandleTransform t;
      t.translation = Vec3(0, 0, 0.4 * i / 40.0);
      s.grab_drag(t);
      if (i > 1) remeshed += s.last_frame().remeshed_vertices, roi += s.last_frame().roi_vertices;
    }
    s.grab_end();
    s.mesh().validate();
    remeshed_fraction = remeshed / roi;
    top = -1e300;
    for (Vertex v : s.mesh().vertices()) top = std::max(top, s.mesh().position(v).z);
    return s.quality();
  };
  double whole_fraction = 0, strained_fraction = 0, whole_top = 0, strained_top = 0;
  const geometry::QualityReport whole = pull(0.0, whole_fraction, whole_top);
  const geometry::QualityReport strained = pull(0.1, strained_fraction, strained_top);
  std::printf("pull: remeshed %.0f %% of the ROI per frame (whole region: %.0f %%); min angle %.1f / %.1f deg, "
              "under 30 deg %.3f / %.3f %%\n",
              100 * strained_fraction, 100 * whole_fraction, strained.min_angle_deg, whole.min_angle_deg,
              strained.pct_min_angle_lt_30, whole.pct_min_angle_lt_30);
  EXPECT_GE(whole_fraction, 1.0);  // the ROI and a ring
  EXPECT_LT(strained_fraction, 0.75 * whole_fraction);
  // The release mends the footprint's triangles under 25 degrees (sculpt/grab.h), as the polish
  // of a whole-mesh remesh does.
  EXPECT_GE(strained.min_angle_deg, sculpt::Grab::kMendAngleDeg);
  EXPECT_GE(strained.mean_min_angle_deg, whole.mean_min_angle_deg - 1.0);
  EXPECT_LE(strained.pct_min_angle_lt_30, whole.pct_min_angle_lt_30 + 0.5);
  // The pulled tip went as far either way (the handle moves rigidly, remeshed or not).
  EXPECT_NEAR(strained_top, whole_top, 0.02);
}

// The release's scope: the corners of the triangles under the angle anywhere in the footprint
// (not only the last frame's region) and two rings, within the footprint; nothing where all is
// well shaped.
TEST(RegionStrain, TheReleaseTakesThePoorTrianglesOfTheFootprintAndTwoRings) {
  SphereAfterFirstFrame s;
  auto& [m, region, strain] = s;
  std::vector<Vertex> scope;
  strain.select_release(m, region, 25.0, scope);
  EXPECT_TRUE(scope.empty()) << "an icosphere has no triangle under 25 degrees";
  // One vertex pushed most of the way to a neighbour: the triangles beside that edge get thin.
  const Vertex v(0);
  const Vertex w = *m.vertices(v).begin();
  m.position(v) += 0.8 * (m.position(w) - m.position(v));
  std::set<mesh::Index> poor_corners;
  for (mesh::Face f : m.faces()) {
    Vertex c[3];
    m.face_vertices(f, c);
    const Point &a = m.position(c[0]), &b = m.position(c[1]), &d = m.position(c[2]);
    auto angle = [](const Point& p, const Point& x, const Point& y) {
      return std::acos(glm::dot(glm::normalize(x - p), glm::normalize(y - p))) * 180.0 / M_PI;
    };
    if (std::min({angle(a, b, d), angle(b, d, a), angle(d, a, b)}) < 25.0)
      for (Vertex u : c) poor_corners.insert(u.idx);
  }
  ASSERT_FALSE(poor_corners.empty());
  std::set<mesh::Index> expected;
  for (mesh::Index i : poor_corners) {
    const std::set<mesh::Index> near = within_rings(m, Vertex(i), sculpt::RegionStrain::kScopeRings);
    expected.insert(near.begin(), near.end());
  }
  strain.select_release(m, region, 25.0, scope);
  EXPECT_EQ(indices(scope), expected);
  // Only within the footprint: without v's half of the sphere, none of it.
  std::vector<Vertex> half;
  for (Vertex u : region)
    if (glm::dot(m.position(u), m.position(v)) < 0) half.push_back(u);
  strain.select_release(m, half, 25.0, scope);
  EXPECT_TRUE(scope.empty());
}
