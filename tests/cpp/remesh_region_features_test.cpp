// Features where a sculpting frame's region meets them (issue 17, item 3): region iterations must
// keep sharp edges and the region's border as well shaped as whole-mesh remeshing does.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "geometry/quality.h"
#include "mesh/primitives.h"
#include "sculpt/session.h"

using namespace adasculpt;

namespace {

// The held-out case of the issue: a 4 x 1 x 1 bar with sharp edges (features 45), its far end
// twisted by 180 degrees about its axis with a grab, the region of interest ending halfway along.
nlohmann::json twist_session(int substeps) {
  return nlohmann::json::parse(R"({"version": 1,
    "settings": {"epsilon": "0.05%", "min_length": "0.2%", "max_length": "5%", "features": 45},
    "steps": [{"grab": {"center": [2, 0, 0], "handle_radius": 0.6, "roi_radius": 3.5,
                        "rotate": {"axis": [1, 0, 0], "degrees": 180}, "substeps": )" +
                               std::to_string(substeps) + "}}]}");
}

}  // namespace

TEST(RemeshRegionFeatures, TwistedBarKeepsWellShapedTrianglesWhereTheRegionMeetsSharpEdges) {
  sculpt::Session s;
  s.load(mesh::make_box(32, 8, 8, 4.0, 1.0, 1.0));
  s.replay(twist_session(30));
  ASSERT_NO_THROW(s.mesh().validate());
  const geometry::QualityReport q = s.quality();
  // Before: the held feature vertices on the region's border took the zero sizing of unmeasured
  // neighbours outside the region, their edges were split every frame, and a strip of 0.4 degree
  // slivers (and twice the vertices) grew there.
  EXPECT_GE(q.min_angle_deg, 20.0);
  EXPECT_GE(q.mean_min_angle_deg, 45.0);
  EXPECT_LT(q.vertices, 3500u);
  EXPECT_EQ(q.genus, 0);
  EXPECT_EQ(q.components, 1);
}
