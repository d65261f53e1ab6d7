// Session files: round trip through the parser and one-line errors naming step and field.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "sculpt/session_file.h"

using namespace adasculpt;
using nlohmann::json;

namespace {
std::string error_of(const std::string& text) {
  try {
    sculpt::parse_session_file(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}
const char* kGood = R"({"version": 1, "settings": {"epsilon": "0.05%", "min_length": 0.01, "features": 45},
  "steps": [
    {"grab": {"center": [0, 0, 1], "handle_radius": 0.1, "roi_radius": 0.8, "translate": [0, 0, 1.5],
              "rotate": {"axis": [0, 1, 0], "degrees": 30}, "scale": 0.8, "substeps": 20}},
    {"grab": {"center": [1, 0, 0], "handle_radius": 0, "roi_radius": 0.5}},
    {"remesh": {"iterations": 3}}, {"undo": 2}, {"redo": 1}]})";
}  // namespace

TEST(SculptSessionFile, RoundTrip) {
  const sculpt::SessionFile f = sculpt::parse_session_file(std::string(kGood));
  ASSERT_EQ(f.steps.size(), 5u);
  EXPECT_TRUE(f.settings.epsilon->percent);
  EXPECT_DOUBLE_EQ(f.settings.epsilon->value, 0.05);
  EXPECT_EQ(f.steps[0].grab.substeps, 20);
  EXPECT_EQ(f.steps[1].grab.substeps, 1);
  EXPECT_EQ(f.steps[1].grab.scale, 1.0);
  EXPECT_EQ(f.steps[2].count, 3);
  EXPECT_EQ(f.steps[3].kind, sculpt::SessionStep::Kind::Undo);
  const json again = sculpt::to_json(f);
  const sculpt::SessionFile g = sculpt::parse_session_file(again);
  EXPECT_EQ(sculpt::to_json(g), again);
  EXPECT_EQ(again["settings"]["epsilon"], "0.05%");
  // Totals: the fraction of each part.
  const auto half = f.steps[0].grab.total_at(0.5);
  EXPECT_DOUBLE_EQ(half.translation.z, 0.75);
  EXPECT_DOUBLE_EQ(half.scale, 0.9);
  EXPECT_NEAR(glm::degrees(glm::angle(half.rotation)), 15.0, 1e-9);
}

TEST(SculptSessionFile, ErrorsNameStepAndField) {
  EXPECT_EQ(error_of(R"({"version": 1, "steps": [{"remesh": {"iterations": 1}}, {"undo": 1},
      {"grab": {"center": [0,0,0], "handle_radius": 0.1, "roi_radius": -1}}]})"),
            "step 3 (grab): 'roi_radius' must be a positive number");
  EXPECT_EQ(error_of(R"({"version": 1, "steps": [{"grab": {"handle_radius": 0.1, "roi_radius": 1}}]})"),
            "step 1 (grab): 'center' is missing");
  EXPECT_EQ(error_of(R"({"version": 1, "steps": [{"grab": {"center": [0,0], "handle_radius": 0.1, "roi_radius": 1}}]})"),
            "step 1 (grab): 'center' must be an array of 3 numbers");
  EXPECT_EQ(error_of(R"({"version": 1, "steps": [{"grab": {"center": [0,0,0], "handle_radius": 0.1, "roi_radius": 1,
      "substeps": 0}}]})"),
            "step 1 (grab): 'substeps' must be a positive integer (at most 1000000)");
  EXPECT_EQ(error_of(R"({"version": 1, "steps": [{"grab": {"center": [0,0,0], "handle_radius": 0.1, "roi_radius": 1,
      "rotate": {"axis": [0,0,0], "degrees": 3}}}]})"),
            "step 1 (grab): 'rotate.axis' must not be the zero vector");
  EXPECT_EQ(error_of(R"({"version": 1, "steps": [{"remesh": {"iterations": 2.5}}]})"),
            "step 1 (remesh): 'iterations' must be a positive integer");
  EXPECT_EQ(error_of(R"({"version": 1, "steps": [{"smooth": 1}]})"),
            "step 1: unknown step 'smooth' (expected grab, brush, remesh, mask, undo or redo)");
  EXPECT_EQ(error_of(R"({"version": 1, "steps": [{"undo": -1}]})"),
            "step 1 (undo): 'undo' must be a positive integer (at most 1000000)");
  EXPECT_EQ(error_of(R"({"version": 2, "steps": []})"), "session file: 'version' must be 1");
  EXPECT_EQ(error_of(R"({"version": 1})"), "session file: 'steps' must be an array");
  EXPECT_EQ(error_of(R"({"version": 1, "settings": {"epsilon": "abc%"}, "steps": []})"),
            "settings: 'epsilon' must be a positive number or a percentage string like \"0.5%\"");
  EXPECT_EQ(error_of(R"({"version": 1, "settings": {"eps": 1}, "steps": []})"), "settings: unknown field 'eps'");
  EXPECT_EQ(error_of(R"({"version": 1, "steps": [{"grab": {"center": [0,0,0], "handle_radius": 0.1,
      "roi_radius": 1, "translation": [1,0,0]}}]})"),
            "step 1 (grab): unknown field 'translation'");
  const std::string bad_json = error_of("{\"version\": 1, ");
  EXPECT_EQ(bad_json.rfind("session file: not valid JSON", 0), 0u) << bad_json;
  for (const std::string& e : {bad_json, error_of(R"({"version": 1, "steps": [{"undo": "x"}]})")})
    EXPECT_EQ(e.find('\n'), std::string::npos);
}

// The brush settings alone (what the wasm brushBegin takes) and inside a brush step.
TEST(SculptSessionFile, BrushSettingsAloneAndInAStep) {
  const json settings = {{"tool", "crease"}, {"radius", 0.2}, {"strength", 0.7}, {"symmetry", "y"}, {"invert", true}};
  const deform::BrushSettings s = sculpt::parse_brush_settings(settings);
  EXPECT_EQ(s.tool, deform::BrushTool::Crease);
  EXPECT_DOUBLE_EQ(s.radius, 0.2);
  EXPECT_DOUBLE_EQ(s.strength, 0.7);
  EXPECT_EQ(s.symmetry_axis, 1);
  EXPECT_TRUE(s.invert);
  EXPECT_DOUBLE_EQ(s.spacing, 0.25);

  auto error = [](const json& j) {
    try {
      sculpt::parse_brush_settings(j);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  // A stroke's own keys are not settings: only a step (which passes them as stroke_keys) may hold them.
  json with_path = settings;
  with_path["path"] = json::array({json::array({0, 0, 1})});
  EXPECT_EQ(error(with_path), "brush: unknown field 'path'");
  EXPECT_EQ(sculpt::parse_brush_settings(with_path, "brush: ", {"path"}).tool, deform::BrushTool::Crease);
  EXPECT_EQ(error({{"radius", 0.1}}), "brush: 'tool' is missing");
  EXPECT_EQ(error({{"tool", "hammer"}, {"radius", 0.1}}),
            "brush: 'tool' must be one of draw, inflate, smooth, flatten, pinch, crease, snakeHook");
  EXPECT_EQ(error({{"tool", "draw"}, {"radius", 0.1}, {"symmetry", "w"}}), "brush: 'symmetry' must be one of x, y, z, none");

  json step = settings;
  step["path"] = json::array({json::array({0, 0, 1}), json::array({0, 0.1, 1})});
  const sculpt::SessionFile f = sculpt::parse_session_file(json{{"version", 1}, {"steps", json::array({{{"brush", step}}})}});
  ASSERT_EQ(f.steps.size(), 1u);
  EXPECT_EQ(f.steps[0].brush.settings.tool, deform::BrushTool::Crease);
  EXPECT_EQ(f.steps[0].brush.path.size(), 2u);
  json no_path = settings;
  EXPECT_EQ(error_of(json{{"version", 1}, {"steps", json::array({{{"brush", no_path}}})}}.dump()),
            "step 1 (brush): 'path' is missing");
}
