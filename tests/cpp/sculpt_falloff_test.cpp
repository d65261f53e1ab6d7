// Brush feel and detail control (issue 19): the falloff presets' shapes, strokes with each preset keep
// the mesh valid and differ in profile, session files carry the falloff (old files replay as before),
// and the detail flood fill (a whole-mesh remesh at a constant edge length) gives that edge length in
// one undo step.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "deform/brushes.h"
#include "geometry/quality.h"
#include "mesh/primitives.h"
#include "sculpt/session.h"
#include "sculpt/session_file.h"

using namespace adasculpt;
using deform::BrushFalloff;
using deform::BrushTool;

namespace {

const BrushFalloff kAll[] = {BrushFalloff::Smooth, BrushFalloff::Sphere, BrushFalloff::Sharp, BrushFalloff::Linear,
                             BrushFalloff::Constant};

sculpt::BrushStroke stroke_over_the_pole(BrushTool tool, BrushFalloff falloff) {
  sculpt::BrushStroke st;
  st.settings.tool = tool;
  st.settings.radius = 0.35;
  st.settings.strength = 0.8;
  st.settings.falloff = falloff;
  for (int i = 0; i <= 12; ++i) st.path.push_back(Point(glm::normalize(Vec3(0.05 * i - 0.3, 0.05, 1))));
  return st;
}

// How far a vertex at `angle` radians from +z moved off the unit sphere, after one draw stamp at the
// pole (averaged over the vertices within 0.04 of that angle).
double raise_at(const mesh::SurfaceMesh& m, double angle) {
  double sum = 0;
  int n = 0;
  for (mesh::Vertex v : m.vertices()) {
    const Point& p = m.position(v);
    const double a = std::acos(std::min(1.0, p.z / glm::length(p)));
    if (std::abs(a - angle) > 0.04) continue;
    sum += glm::length(p) - 1;
    ++n;
  }
  return n ? sum / n : 0;
}

double mean_edge(const mesh::SurfaceMesh& m) {
  double sum = 0;
  size_t n = 0;
  for (mesh::Edge e : m.edges()) {
    sum += glm::length(m.position(m.vertex(e, 0)) - m.position(m.vertex(e, 1)));
    ++n;
  }
  return sum / double(n);
}

}  // namespace

TEST(SculptFalloff, EachPresetHasItsShape) {
  using deform::brush_falloff;
  struct Expected {
    BrushFalloff f;
    double at_half;
  };
  const Expected cases[] = {{BrushFalloff::Smooth, 0.421875},           // (1 - 1/4)^3
                            {BrushFalloff::Sphere, std::sqrt(0.75)},    // sqrt(1 - 1/4)
                            {BrushFalloff::Sharp, 0.25},                // (1 - 1/2)^2
                            {BrushFalloff::Linear, 0.5},
                            {BrushFalloff::Constant, 1}};
  for (const Expected& c : cases) {
    const std::string name = deform::brush_falloff_name(c.f);
    EXPECT_DOUBLE_EQ(brush_falloff(0, 2, c.f), 1) << name;
    EXPECT_NEAR(brush_falloff(1, 2, c.f), c.at_half, 1e-15) << name;
    EXPECT_EQ(brush_falloff(2, 2, c.f), 0) << name;  // the rim is outside, for every preset
    EXPECT_EQ(brush_falloff(5, 2, c.f), 0) << name;
    double prev = 1;
    for (int i = 0; i <= 200; ++i) {
      const double w = brush_falloff(2.0 * i / 200, 2, c.f);
      EXPECT_LE(w, prev) << name << " is not monotone at q = " << i / 200.0;
      EXPECT_GE(w, 0) << name;
      prev = w;
    }
    EXPECT_EQ(deform::parse_brush_falloff(name), c.f);
  }
  EXPECT_DOUBLE_EQ(brush_falloff(1, 2), brush_falloff(1, 2, BrushFalloff::Smooth));  // today's curve by default
  EXPECT_FALSE(deform::parse_brush_falloff("soft").has_value());
}

TEST(SculptFalloff, StrokesWithEveryPresetKeepTheMeshValid) {
  for (BrushTool tool : {BrushTool::Draw, BrushTool::Inflate, BrushTool::Smooth, BrushTool::Crease, BrushTool::Grab}) {
    for (BrushFalloff f : kAll) {
      sculpt::Session s;
      s.load(mesh::make_icosphere(4));
      sculpt::BrushStroke st = stroke_over_the_pole(tool, f);
      if (tool == BrushTool::Grab)  // the snake hook's samples are the pointer in space, off the surface
        for (size_t i = 0; i < st.path.size(); ++i) st.path[i] = st.path[0] + Vec3(0.02 * double(i), 0, 0.02 * double(i));
      s.brush_stroke(st);
      const std::string what = std::string(deform::brush_tool_name(tool)) + " " + deform::brush_falloff_name(f);
      s.mesh().validate();
      const geometry::QualityReport q = s.quality();
      EXPECT_EQ(q.genus, 0) << what;
      EXPECT_EQ(q.components, 1) << what;
      EXPECT_GT(q.min_angle_deg, 5) << what;
    }
  }
}

TEST(SculptFalloff, OneStampsProfileFollowsThePreset) {
  // One draw stamp at the pole, radius 0.5 rad: the raise at 0.25 rad (q about 0.52) over the raise
  // at the centre, which the curves at q = 0.52 order as sharp 0.23 < smooth 0.39 < linear 0.48 <
  // sphere 0.85 < constant 1.
  auto profile = [](BrushFalloff f) {
    sculpt::Session s;
    s.load(mesh::make_icosphere(5));
    s.set_settings({{"min_length", 0.001}, {"max_length", 1.0}, {"epsilon", 1.0}});  // keep the vertices
    sculpt::BrushStroke st;
    st.settings.tool = BrushTool::Draw;
    st.settings.radius = std::sin(0.5);
    st.settings.strength = 1;
    st.settings.falloff = f;
    st.path.push_back(Point(0, 0, 1));
    s.brush_stroke(st);
    return raise_at(s.mesh(), 0.25) / raise_at(s.mesh(), 0.04);  // the band around the pole
  };
  double prev = 0;
  for (BrushFalloff f : {BrushFalloff::Sharp, BrushFalloff::Smooth, BrushFalloff::Linear, BrushFalloff::Sphere,
                         BrushFalloff::Constant}) {
    const double ratio = profile(f);
    EXPECT_GT(ratio, prev + 0.05) << deform::brush_falloff_name(f);
    prev = ratio;
  }
  EXPECT_GT(prev, 0.9);  // constant: the rim rises as far as the centre
}

TEST(SculptFalloff, SessionFilesCarryTheFalloffAndOldFilesReplayAsBefore) {
  const nlohmann::json step = {{"tool", "draw"}, {"radius", 0.3}, {"path", {{0, 0, 1}, {0.1, 0, 1}}}};
  nlohmann::json with = step;
  with["falloff"] = "sharp";
  auto file = [](const nlohmann::json& b) { return nlohmann::json{{"version", 1}, {"steps", {{{"brush", b}}}}}; };

  const sculpt::SessionFile old_file = sculpt::parse_session_file(file(step));
  EXPECT_EQ(old_file.steps[0].brush.settings.falloff, BrushFalloff::Smooth);
  EXPECT_FALSE(sculpt::to_json(old_file)["steps"][0]["brush"].contains("falloff"));  // written as it was read

  const sculpt::SessionFile parsed = sculpt::parse_session_file(file(with));
  EXPECT_EQ(parsed.steps[0].brush.settings.falloff, BrushFalloff::Sharp);
  EXPECT_EQ(sculpt::to_json(parsed)["steps"][0]["brush"]["falloff"], "sharp");

  // The explicit default replays the old file exactly.
  nlohmann::json smooth = step;
  smooth["falloff"] = "smooth";
  sculpt::Session a, b, c;
  for (sculpt::Session* s : {&a, &b, &c}) s->load(mesh::make_icosphere(3));
  a.replay(file(step));
  b.replay(file(smooth));
  c.replay(file(with));
  ASSERT_EQ(a.mesh().vertices_size(), b.mesh().vertices_size());
  for (mesh::Vertex v : a.mesh().vertices()) ASSERT_EQ(a.mesh().position(v), b.mesh().position(v));
  bool differs = a.mesh().vertices_size() != c.mesh().vertices_size();
  for (mesh::Vertex v : a.mesh().vertices())
    differs = differs || (v.idx < c.mesh().vertices_size() && a.mesh().position(v) != c.mesh().position(v));
  EXPECT_TRUE(differs);

  nlohmann::json bad = step;
  bad["falloff"] = "soft";
  try {
    sculpt::parse_session_file(file(bad));
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "step 1 (brush): 'falloff' must be one of smooth, sphere, sharp, linear, constant");
  }
}

TEST(SculptFalloff, DetailFloodFillGivesTheDetailsEdgeLengthInOneUndoStep) {
  for (double detail : {0.05, 0.12}) {
    sculpt::Session s;
    s.load(mesh::make_icosphere(4));  // edges about 0.08
    const size_t before = s.mesh().n_vertices();
    s.remesh(5, detail);
    s.mesh().validate();
    EXPECT_NEAR(mean_edge(s.mesh()), detail, 0.15 * detail) << "detail " << detail;
    EXPECT_TRUE(s.undo());
    EXPECT_EQ(s.mesh().n_vertices(), before);
    EXPECT_FALSE(s.can_undo());
  }
  sculpt::Session s;
  s.load(mesh::make_icosphere(2));
  EXPECT_THROW(s.remesh(1, -1), std::invalid_argument);
  EXPECT_THROW(s.remesh(1, std::nan("")), std::invalid_argument);
}

TEST(SculptFalloff, ARemeshStepsDetailReplaysAndRoundTrips) {
  const nlohmann::json f = {{"version", 1}, {"steps", {{{"remesh", {{"iterations", 3}, {"detail", 0.1}}}}}}};
  const sculpt::SessionFile parsed = sculpt::parse_session_file(f);
  EXPECT_EQ(parsed.steps[0].detail, 0.1);
  EXPECT_EQ(sculpt::to_json(parsed)["steps"][0]["remesh"]["detail"], 0.1);
  sculpt::Session replayed, direct;
  replayed.load(mesh::make_icosphere(4));
  direct.load(mesh::make_icosphere(4));
  replayed.replay(f);
  direct.remesh(3, 0.1);
  ASSERT_EQ(replayed.mesh().vertices_size(), direct.mesh().vertices_size());
  for (mesh::Vertex v : direct.mesh().vertices()) ASSERT_EQ(replayed.mesh().position(v), direct.mesh().position(v));
}
