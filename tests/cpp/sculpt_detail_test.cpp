// Detail that follows the object (issue 18): a stroke applies the detail settings to the connected
// component under the brush, so the same stroke on the same object changes it the same way
// whether the scene holds one copy or sixteen; and a stroke's own detail (the viewer's
// screen-pixel mode) sets the edge length it remeshes to.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "io/load_mesh.h"
#include "mesh/build_from_triangles.h"
#include "mesh/primitives.h"
#include "sculpt/session.h"
#include "sculpt_test_util.h"

using namespace adasculpt;

namespace {

using test::sphere_copies;

sculpt::BrushStroke draw_on_first_sphere(double detail = 0) {
  sculpt::BrushStroke st;
  st.settings.tool = deform::BrushTool::Draw;
  st.settings.radius = 0.3;
  st.settings.detail = detail;
  for (int i = 0; i < 8; ++i) st.path.push_back(Point(glm::normalize(Vec3(0.06 * i - 0.2, 0.1, 1))));
  return st;
}

// The vertices a stroke added or removed on the first sphere (the others are untouched).
long vertex_change(int copies, const nlohmann::json& settings) {
  sculpt::Session s;
  s.load(sphere_copies(copies));
  s.set_settings(settings);
  const long before = long(s.mesh().n_vertices());
  s.brush_stroke(draw_on_first_sphere());
  s.mesh().validate();
  return long(s.mesh().n_vertices()) - before;
}

}  // namespace

TEST(SculptDetail, AStrokeOnOneOfSixteenObjectsKeepsThatObjectsDetail) {
  // Detail as percentages of the diagonal, as the app's defaults are: on 16 spheres in a row the
  // scene's diagonal is about 14 times one sphere's.
  const nlohmann::json settings = {{"epsilon", "0.05%"}, {"min_length", "0.2%"}, {"max_length", "5%"}};
  const long one = vertex_change(1, settings), sixteen = vertex_change(16, settings);
  EXPECT_GT(std::abs(one), 10) << "the stroke was meant to remesh the region";
  // The same detail on the same sphere: the same change, up to the rounding of the scaling.
  EXPECT_NEAR(double(sixteen), double(one), 0.05 * std::abs(double(one)) + 4) << one << " vs " << sixteen;
}

TEST(SculptDetail, AStrokesOwnDetailSetsItsEdgeLength) {
  for (double detail : {0.04, 0.08}) {
    sculpt::Session s;
    s.load(mesh::make_icosphere(4));  // edges about 0.08
    s.brush_stroke(draw_on_first_sphere(detail));
    s.mesh().validate();
    // Edges near the middle of the stroke: close to the stroke's detail.
    const Point centre(glm::normalize(Vec3(0.0, 0.1, 1)));
    double sum = 0;
    int n = 0;
    const mesh::SurfaceMesh& m = s.mesh();
    for (mesh::Edge e : m.edges()) {
      const Point a = m.position(m.vertex(e, 0)), b = m.position(m.vertex(e, 1));
      if (glm::length(0.5 * (a + b) - centre) > 0.1) continue;
      sum += glm::length(b - a);
      ++n;
    }
    ASSERT_GT(n, 5);
    EXPECT_NEAR(sum / n, detail, 0.35 * detail) << "detail " << detail;
  }
}

TEST(SculptDetail, DetailMustBeANonNegativeLength) {
  sculpt::Session s;
  s.load(mesh::make_icosphere(2));
  deform::BrushSettings b;
  b.radius = 0.3;
  b.detail = -1;
  EXPECT_THROW(s.brush_begin(b), std::invalid_argument);
  b.detail = std::nan("");
  EXPECT_THROW(s.brush_begin(b), std::invalid_argument);
}
