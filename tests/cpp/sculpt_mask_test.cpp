// The sculpting mask through the Session: masked vertices never move under any brush or the pull
// and their triangles are not remeshed; every mask operation is one undo step, replays from a
// session file and survives the saved state.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "sculpt/session_file.h"
#include "sculpt_mask_test_util.h"
#include "undo_test_util.h"

using namespace adasculpt;
using mesh::Vertex;
using sculpt::MaskOp;
using sculpt::MaskOpKind;

namespace {

// A path over the sphere's -y side from below the masked cap's rim (z = 0.28) to well inside it.
std::vector<Point> across_the_rim() {
  std::vector<Point> path;
  for (int i = 0; i <= 12; ++i) {
    const double z = -0.6 + 1.4 * i / 12.0;
    path.push_back(Point(0.15 * std::sin(i), -std::sqrt(1 - z * z), z));
  }
  return path;
}

sculpt::BrushStroke stroke(deform::BrushTool tool, std::vector<Point> path) {
  sculpt::BrushStroke b;
  b.settings.tool = tool;
  b.settings.radius = 0.35;
  b.settings.strength = 1;
  b.path = std::move(path);
  return b;
}

std::vector<float> mask_of(const sculpt::Session& s) {
  std::vector<float> out;
  for (size_t i = 0; i < s.mesh().vertices_size(); ++i) out.push_back(s.mask_value(Vertex(mesh::Index(i))));
  return out;
}

// Positions bit for bit and mask values, slot by slot.
::testing::AssertionResult same_state(const sculpt::Session& a, const sculpt::Session& b) {
  const mesh::SurfaceMesh &x = a.mesh(), &y = b.mesh();
  if (x.vertices_size() != y.vertices_size() || x.faces_size() != y.faces_size())
    return ::testing::AssertionFailure() << "slot counts differ";
  for (Vertex v : x.vertices())
    if (std::memcmp(&x.position(v), &y.position(v), sizeof(Point)) != 0 || y.is_deleted(v))
      return ::testing::AssertionFailure() << "vertex " << v.idx << " differs";
  if (mask_of(a) != mask_of(b)) return ::testing::AssertionFailure() << "the masks differ";
  return ::testing::AssertionSuccess();
}

MaskOp whole(MaskOpKind k) {
  MaskOp op;
  op.kind = k;
  return op;
}

}  // namespace

TEST(SculptMask, MaskedHalfStaysBitIdenticalThroughEveryBrushAndThePull) {
  sculpt::Session s;
  s.load(mesh::make_icosphere(4));
  test::mask_north_cap(s);
  const auto positions = test::masked_positions(s.mesh());
  const auto triangles = test::masked_triangles(s.mesh());
  ASSERT_GT(positions.size(), s.mesh().n_vertices() / 4);  // a real part of the sphere
  ASSERT_LT(positions.size(), s.mesh().n_vertices() * 3 / 4);
  const size_t vertices_before = s.mesh().n_vertices();
  using deform::BrushTool;
  for (BrushTool tool : {BrushTool::Draw, BrushTool::Inflate, BrushTool::Smooth, BrushTool::Flatten, BrushTool::Pinch,
                         BrushTool::Crease}) {
    s.brush_stroke(stroke(tool, across_the_rim()));
    s.mesh().validate();
    EXPECT_EQ(test::masked_positions(s.mesh()), positions) << deform::brush_tool_name(tool);
    EXPECT_EQ(test::masked_triangles(s.mesh()), triangles) << deform::brush_tool_name(tool);
  }
  // The snake hook drags what is under the pointer into space, here up across the cap.
  s.brush_stroke(stroke(BrushTool::Grab, {Point(0, -1, 0), Point(0, -1.2, 0.3), Point(0, -1.3, 0.7)}));
  EXPECT_EQ(test::masked_positions(s.mesh()), positions) << "snake hook";
  EXPECT_EQ(test::masked_triangles(s.mesh()), triangles) << "snake hook";
  // The pull: a handle just below the rim, its region of interest well inside the cap.
  s.grab_begin(Point(0, -0.97, 0.2), 0.15, 0.9);
  for (int i = 1; i <= 8; ++i) {
    deform::HandleTransform t;
    t.translation = (i / 8.0) * Vec3(0, -0.5, 0.3);
    s.grab_drag(t);
  }
  s.grab_end();
  s.mesh().validate();
  EXPECT_EQ(test::masked_positions(s.mesh()), positions) << "pull";
  EXPECT_EQ(test::masked_triangles(s.mesh()), triangles) << "pull";
  // And the strokes did sculpt the unmasked part (the test would pass on a frozen mesh otherwise).
  EXPECT_NE(s.mesh().n_vertices(), vertices_before);
  double lowest = 0;
  for (Vertex v : s.mesh().vertices()) lowest = std::min(lowest, s.mesh().position(v).y);
  EXPECT_LT(lowest, -1.2);
}

TEST(SculptMask, WholeMeshRemeshLeavesMaskedTrianglesAndTheirRingAlone) {
  sculpt::Session s;
  s.load(mesh::make_icosphere(3));
  s.set_settings({{"epsilon", "0.01%"}, {"min_length", "0.5%"}});  // finer: every edge wants splitting
  test::mask_north_cap(s);
  const auto positions = test::masked_positions(s.mesh());
  const auto triangles = test::masked_triangles(s.mesh());
  const size_t before = s.mesh().n_vertices();
  s.remesh(2);
  s.mesh().validate();
  EXPECT_GT(s.mesh().n_vertices(), before + before / 4);  // the unmasked part was refined
  EXPECT_EQ(test::masked_positions(s.mesh()), positions);
  EXPECT_EQ(test::masked_triangles(s.mesh()), triangles);
}

TEST(SculptMask, OperationsDoWhatTheirNamesSay) {
  sculpt::Session s;
  s.load(mesh::make_icosphere(3));
  EXPECT_FALSE(mesh::find_mask(s.mesh()).is_valid());  // no mask until the first operation
  MaskOp paint;
  paint.kind = MaskOpKind::Paint;
  paint.path = {Point(0, 0, 1)};
  paint.radius = 0.5;
  paint.strength = 0.8;
  s.mask(paint);
  for (Vertex v : s.mesh().vertices()) {
    const double d = glm::length(s.mesh().position(v) - Point(0, 0, 1));
    EXPECT_FLOAT_EQ(s.mask_value(v), float(0.8 * sculpt::mask_falloff(d, 0.5))) << v.idx;
  }
  // Paint never lowers: a weaker stroke over the same place changes nothing.
  const std::vector<float> painted = mask_of(s);
  paint.strength = 0.3;
  s.mask(paint);
  EXPECT_EQ(mask_of(s), painted);
  s.mask(whole(MaskOpKind::Invert));
  for (size_t i = 0; i < painted.size(); ++i) EXPECT_EQ(mask_of(s)[i], 1.0f - painted[i]);
  s.mask(whole(MaskOpKind::Invert));
  const std::vector<float> unsharp = mask_of(s);  // (1 - (1 - m) need not be m in floats)
  s.mask(whole(MaskOpKind::Sharpen));  // away from 1/2: a 0.8 becomes 0.896
  for (size_t i = 0; i < unsharp.size(); ++i) {
    const float m = unsharp[i];
    EXPECT_FLOAT_EQ(mask_of(s)[i], m * m * (3 - 2 * m));
  }
  // Blur spreads the mask one ring out, and keeps it in [0, 1].
  size_t nonzero_before = 0, nonzero_after = 0;
  for (float m : mask_of(s)) nonzero_before += m > 0;
  s.mask(whole(MaskOpKind::Blur));
  for (float m : mask_of(s)) {
    nonzero_after += m > 0;
    EXPECT_TRUE(m >= 0 && m <= 1);
  }
  EXPECT_GT(nonzero_after, nonzero_before);
  s.mask(whole(MaskOpKind::Fill));
  for (float m : mask_of(s)) EXPECT_EQ(m, 1.0f);
  s.mask(whole(MaskOpKind::Clear));
  for (float m : mask_of(s)) EXPECT_EQ(m, 0.0f);
  EXPECT_EQ(s.undo_steps(), 8u);  // one step each
}

TEST(SculptMask, PartlyMaskedVerticesMoveByTheUnmaskedFraction) {
  // The same draw stroke without remeshing effects: an exact measure needs the same mesh, so
  // compare one brush stamp (the deformer) on a mesh masked at 0.25 everywhere with an unmasked one.
  mesh::SurfaceMesh free = mesh::make_icosphere(3), held = free;
  auto mask = held.add_vertex_property<float>(mesh::kMaskProperty, 0.25f);
  deform::BrushSettings st;
  st.tool = deform::BrushTool::Draw;
  st.radius = 0.5;
  st.strength = 1;
  deform::StampSpec stamp;
  stamp.center = Point(0, 0, 1);
  stamp.seed = deform::walk_to_nearest_vertex(free, Vertex(0), stamp.center);
  deform::BrushDeformer a, b;
  a.apply(free, st, &stamp, 1);
  b.apply(held, st, &stamp, 1);
  const mesh::SurfaceMesh original = mesh::make_icosphere(3);
  size_t moved = 0;
  for (Vertex v : original.vertices()) {
    const Vec3 full = free.position(v) - original.position(v);
    const Vec3 part = held.position(v) - original.position(v);
    EXPECT_NEAR(glm::length(part - 0.75 * full), 0.0, 1e-15) << v.idx;
    moved += glm::length(full) > 0;
  }
  EXPECT_GT(moved, 10u);
  (void)mask;
}

TEST(SculptMask, EveryOperationIsOneExactUndoStep) {
  sculpt::Session s;
  s.set_history_verification(true);
  s.load(mesh::make_icosphere(3));
  std::vector<std::vector<float>> masks;
  std::vector<std::vector<Point>> positions;
  auto record = [&] {
    masks.push_back(mask_of(s));
    positions.push_back(s.mesh().positions());
  };
  record();
  s.mask(whole(MaskOpKind::Fill));  // the first: gives the mesh its mask
  record();
  s.mask(whole(MaskOpKind::Invert));
  record();
  s.brush_stroke(stroke(deform::BrushTool::Inflate, across_the_rim()));
  record();
  MaskOp erase;
  erase.kind = MaskOpKind::Erase;
  erase.path = across_the_rim();
  erase.radius = 0.3;
  s.mask(erase);
  record();
  s.mask(whole(MaskOpKind::Blur));
  record();
  EXPECT_EQ(s.history_full_diffs(), 0u);
  const size_t steps = s.undo_steps();
  ASSERT_EQ(steps, masks.size() - 1);
  auto check = [&](size_t i) {
    EXPECT_EQ(mask_of(s), masks[i]) << "state " << i;
    EXPECT_EQ(s.mesh().positions(), positions[i]) << "state " << i;
  };
  for (size_t i = steps; i-- > 0;) {
    ASSERT_TRUE(s.undo());
    check(i);
  }
  for (size_t i = 1; i <= steps; ++i) {
    ASSERT_TRUE(s.redo());
    check(i);
  }
}

TEST(SculptMask, SessionFileStepsReplayAndRoundTrip) {
  const nlohmann::json file = {
      {"version", 1},
      {"steps",
       {{{"mask", {{"op", "fill"}}}},
        {{"mask", {{"op", "erase"}, {"path", {{0, 0, -1}}}, {"radius", 1.6}}}},
        {{"brush", {{"tool", "draw"}, {"path", {{0, -1, 0}, {0, -0.9, 0.44}}}, {"radius", 0.35}, {"strength", 1}}}},
        {{"mask", {{"op", "paint"}, {"path", {{0, -1, 0}, {0.3, -0.95, 0}}}, {"radius", 0.3}, {"strength", 0.5}}}},
        {{"mask", {{"op", "sharpen"}}}},
        {{"undo", 1}},
        {{"redo", 1}}}}};
  sculpt::Session a, b, c;
  for (sculpt::Session* s : {&a, &b, &c}) s->load(mesh::make_icosphere(3));
  a.replay(file);
  b.replay(sculpt::to_json(sculpt::parse_session_file(file)));  // the same after a round trip
  EXPECT_TRUE(same_state(a, b));
  // The same operations called directly.
  const sculpt::SessionFile parsed = sculpt::parse_session_file(file);
  for (const sculpt::SessionStep& st : parsed.steps)
    if (st.kind == sculpt::SessionStep::Kind::Mask) c.mask(st.mask);
    else if (st.kind == sculpt::SessionStep::Kind::Brush) c.brush_stroke(st.brush);
  EXPECT_TRUE(same_state(a, c));
  EXPECT_EQ(sculpt::to_json(parsed), sculpt::to_json(sculpt::parse_session_file(sculpt::to_json(parsed))));
}

TEST(SculptMask, BadMaskStepsAreRefusedNamingTheField) {
  auto error = [](const nlohmann::json& step) {
    try {
      sculpt::parse_session_file(nlohmann::json{{"version", 1}, {"steps", {step}}});
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(error({{"mask", {{"op", "smudge"}}}}),
            "step 1 (mask): 'op' must be one of paint, erase, clear, fill, invert, blur, sharpen");
  EXPECT_EQ(error({{"mask", {{"op", "paint"}, {"radius", 1}}}}), "step 1 (mask): 'path' is missing");
  EXPECT_EQ(error({{"mask", {{"op", "paint"}, {"path", {{0, 0, 1}}}}}}), "step 1 (mask): 'radius' is missing");
  EXPECT_EQ(error({{"mask", {{"op", "erase"}, {"path", {{0, 0, 1}}}, {"radius", 1}, {"strength", 2}}}}),
            "step 1 (mask): 'strength' must be a number between 0 and 1");
  EXPECT_EQ(error({{"mask", {{"op", "invert"}, {"radius", 1}}}}), "step 1 (mask): unknown field 'radius'");
  sculpt::Session s;
  s.load(mesh::make_icosphere(2));
  MaskOp op;
  op.kind = MaskOpKind::Paint;  // no path
  EXPECT_THROW(s.mask(op), std::invalid_argument);
  EXPECT_EQ(s.undo_steps(), 0u);
}

TEST(SculptMask, SavedStateKeepsTheMaskAndItsHistory) {
  sculpt::Session a;
  a.load(mesh::make_icosphere(3));
  a.brush_stroke(stroke(deform::BrushTool::Draw, across_the_rim()));  // a step from before the mask
  test::mask_north_cap(a);
  a.brush_stroke(stroke(deform::BrushTool::Smooth, across_the_rim()));
  ASSERT_TRUE(a.undo());
  const std::vector<uint8_t> blob = a.save_state();
  sculpt::Session b;
  b.restore_state(blob.data(), blob.size());
  EXPECT_TRUE(same_state(a, b));
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(a.undo() && b.undo());
    EXPECT_TRUE(same_state(a, b)) << "undo " << i;
  }
  ASSERT_TRUE(a.redo() && b.redo() && a.redo() && b.redo() && a.redo() && b.redo() && a.redo() && b.redo());
  EXPECT_TRUE(same_state(a, b));
  EXPECT_EQ(test::without_chain(b.save_state()), test::without_chain(a.save_state()));  // the chain id is new per save
  // A corrupt mask value is refused, and the session keeps what it had.
  std::vector<uint8_t> bad = a.save_state();
  const float nan = std::nanf("");
  const std::string name = mesh::kMaskProperty;
  const auto at = std::search(bad.begin(), bad.end(), name.begin(), name.end());
  ASSERT_NE(at, bad.end());
  // name, u32 element size, u64 byte count, then the first value
  std::memcpy(&*(at + std::ptrdiff_t(name.size() + 4 + 8)), &nan, sizeof nan);
  EXPECT_THROW(b.restore_state(bad.data(), bad.size()), std::invalid_argument);
  EXPECT_TRUE(same_state(a, b));
}

TEST(SculptMask, RandomStrokesAndMaskOpsKeepTheMeshValidAndTheMaskInRange) {
  sculpt::Session s;
  s.load(mesh::make_icosphere(3));
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> u(-1, 1);
  auto surface_point = [&] {
    Point p(u(rng), u(rng), u(rng));
    return glm::length(p) > 0 ? glm::normalize(p) : Point(0, 0, 1);
  };
  size_t vertex_changes = 0;  // net, per stroke
  for (int i = 0; i < 60; ++i) {
    const int what = int(rng() % 5);
    if (what == 0) {
      MaskOp op;
      op.kind = rng() % 2 ? MaskOpKind::Paint : MaskOpKind::Erase;
      op.path = {surface_point(), surface_point()};
      op.radius = 0.2 + 0.5 * std::abs(u(rng));
      op.strength = std::abs(u(rng));
      s.mask(op);
    } else if (what == 1) {
      s.mask(whole(static_cast<MaskOpKind>(2 + rng() % 5)));
    } else {
      const size_t before = s.mesh().n_vertices();
      const auto tool = static_cast<deform::BrushTool>(rng() % 6);
      const Point a = surface_point();
      s.brush_stroke(stroke(tool, {a, glm::normalize(a + 0.5 * surface_point())}));
      vertex_changes += before > s.mesh().n_vertices() ? before - s.mesh().n_vertices() : s.mesh().n_vertices() - before;
    }
    s.mesh().validate();
    for (Vertex v : s.mesh().vertices()) ASSERT_TRUE(s.mask_value(v) >= 0 && s.mask_value(v) <= 1) << i;
  }
  EXPECT_GT(vertex_changes, 300u);  // the remesher did work around partly masked vertices
}
