#include "sculpt/session_file.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "remesh/length_spec.h"

namespace adasculpt::sculpt {

namespace {
using nlohmann::json;

[[noreturn]] void fail_at(const std::string& context, const std::string& field, const std::string& what) {
  throw std::invalid_argument(context + "'" + field + "' " + what);
}

double positive_number(const json& j, const std::string& context, const std::string& field, bool allow_zero = false) {
  if (!j.is_number()) fail_at(context, field, allow_zero ? "must be a non-negative number" : "must be a positive number");
  const double v = j.get<double>();
  if (!std::isfinite(v) || v < 0 || (!allow_zero && v == 0))
    fail_at(context, field, allow_zero ? "must be a non-negative number" : "must be a positive number");
  return v;
}

int positive_int(const json& j, const std::string& context, const std::string& field) {
  if (!j.is_number_integer() && !(j.is_number() && std::floor(j.get<double>()) == j.get<double>()))
    fail_at(context, field, "must be a positive integer");
  const double v = j.get<double>();
  if (!(v >= 1) || v > 1e6) fail_at(context, field, "must be a positive integer (at most 1000000)");
  return static_cast<int>(v);
}

Vec3 vec3(const json& j, const std::string& context, const std::string& field) {
  if (!j.is_array() || j.size() != 3) fail_at(context, field, "must be an array of 3 numbers");
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    if (!j[i].is_number() || !std::isfinite(j[i].get<double>())) fail_at(context, field, "must be an array of 3 numbers");
    v[i] = j[i].get<double>();
  }
  return v;
}

LengthSetting length(const json& j, const std::string& context, const std::string& field) {
  const std::string what = "must be a positive number or a percentage string like \"0.5%\"";
  LengthSetting s;
  if (j.is_number()) {
    s.value = j.get<double>();
  } else if (j.is_string()) {
    const std::string t = j.get<std::string>();
    if (t.empty() || t.back() != '%') fail_at(context, field, what);  // a string is a percentage
    try {
      s = remesh::parse_length_spec(t, field);
    } catch (const std::invalid_argument&) {
      fail_at(context, field, what);
    }
  } else {
    fail_at(context, field, what);
  }
  if (!std::isfinite(s.value) || s.value <= 0) fail_at(context, field, what);
  return s;
}

void check_keys(const json& j, const std::string& context, std::initializer_list<const char*> allowed,
                std::initializer_list<const char*> also_allowed = {}) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || it.key() == a;
    for (const char* a : also_allowed) ok = ok || it.key() == a;
    if (!ok) throw std::invalid_argument(context + "unknown field '" + it.key() + "'");
  }
}

GrabStep parse_grab(const json& g, const std::string& ctx) {
  if (!g.is_object()) throw std::invalid_argument(ctx + "must be an object");
  check_keys(g, ctx, {"center", "handle_radius", "roi_radius", "translate", "rotate", "scale", "substeps"});
  GrabStep s;
  for (const char* k : {"center", "handle_radius", "roi_radius"})
    if (!g.contains(k)) fail_at(ctx, k, "is missing");
  s.center = vec3(g["center"], ctx, "center");
  s.handle_radius = positive_number(g["handle_radius"], ctx, "handle_radius", true);
  s.roi_radius = positive_number(g["roi_radius"], ctx, "roi_radius");
  if (g.contains("translate")) s.translate = vec3(g["translate"], ctx, "translate");
  if (g.contains("rotate")) {
    const json& r = g["rotate"];
    if (!r.is_object()) fail_at(ctx, "rotate", "must be an object {\"axis\": [x,y,z], \"degrees\": a}");
    check_keys(r, ctx + "rotate: ", {"axis", "degrees"});
    if (!r.contains("axis") || !r.contains("degrees"))
      fail_at(ctx, "rotate", "must be an object {\"axis\": [x,y,z], \"degrees\": a}");
    s.axis = vec3(r["axis"], ctx, "rotate.axis");
    // Scaled to its largest component first: the length of [0, 0, 1e308] overflows, and
    // normalizing by it wrote a zero axis back (found by the session_file fuzzer).
    const double largest = std::max({std::abs(s.axis.x), std::abs(s.axis.y), std::abs(s.axis.z)});
    if (!(largest > 0)) fail_at(ctx, "rotate.axis", "must not be the zero vector");
    s.axis = glm::normalize(s.axis / largest);
    if (!r["degrees"].is_number() || !std::isfinite(r["degrees"].get<double>()))
      fail_at(ctx, "rotate.degrees", "must be a number");
    s.degrees = r["degrees"].get<double>();
  }
  if (g.contains("scale")) s.scale = positive_number(g["scale"], ctx, "scale");
  if (g.contains("substeps")) s.substeps = positive_int(g["substeps"], ctx, "substeps");
  return s;
}
const char* const kAxes[] = {"x", "y", "z"};

std::vector<Point> parse_path(const json& j, const std::string& ctx) {
  if (!j.contains("path")) fail_at(ctx, "path", "is missing");
  const json& path = j["path"];
  if (!path.is_array() || path.empty()) fail_at(ctx, "path", "must be a non-empty array of [x,y,z] points");
  std::vector<Point> out;
  for (size_t i = 0; i < path.size(); ++i) out.push_back(vec3(path[i], ctx, "path[" + std::to_string(i) + "]"));
  return out;
}

json path_json(const std::vector<Point>& path) {
  json out = json::array();
  for (const Point& p : path) out.push_back({p.x, p.y, p.z});
  return out;
}

BrushStroke parse_brush(const json& b, const std::string& ctx) {
  BrushStroke s;
  s.settings = parse_brush_settings(b, ctx, {"path", "pressure"});
  s.path = parse_path(b, ctx);
  const json& path = b["path"];
  if (b.contains("pressure")) {
    const json& v = b["pressure"];
    if (!v.is_array() || v.size() != path.size()) fail_at(ctx, "pressure", "must be an array with one number per path point");
    for (const json& x : v) {
      if (!x.is_number() || !(x.get<double>() >= 0 && x.get<double>() <= 1))
        fail_at(ctx, "pressure", "must hold numbers between 0 and 1");
      s.pressure.push_back(x.get<double>());
    }
  }
  return s;
}
}  // namespace

deform::BrushSettings parse_brush_settings(const json& b, const std::string& ctx,
                                           std::initializer_list<const char*> stroke_keys) {
  if (!b.is_object()) throw std::invalid_argument(ctx + "must be an object");
  check_keys(b, ctx, {"tool", "radius", "strength", "spacing", "symmetry", "invert", "detail", "falloff"},
             stroke_keys);
  for (const char* k : {"tool", "radius"})
    if (!b.contains(k)) fail_at(ctx, k, "is missing");
  deform::BrushSettings st;
  const auto tool = b["tool"].is_string() ? deform::parse_brush_tool(b["tool"].get<std::string>()) : std::nullopt;
  if (!tool) fail_at(ctx, "tool", std::string("must be one of ") + deform::brush_tool_list());
  st.tool = *tool;
  st.radius = positive_number(b["radius"], ctx, "radius");
  if (b.contains("strength")) {
    const json& v = b["strength"];
    if (!v.is_number() || !(v.get<double>() >= 0 && v.get<double>() <= 1)) fail_at(ctx, "strength", "must be a number between 0 and 1");
    st.strength = v.get<double>();
  }
  if (b.contains("spacing")) {
    const json& v = b["spacing"];
    if (!v.is_number() || !(v.get<double>() >= 0.05 && v.get<double>() <= 4))
      fail_at(ctx, "spacing", "must be a number between 0.05 and 4 (fraction of the radius)");
    st.spacing = v.get<double>();
  }
  if (b.contains("symmetry")) {
    const json& v = b["symmetry"];
    const std::string a = v.is_string() ? v.get<std::string>() : "?";
    st.symmetry_axis = a == "none" ? -1 : a == "x" ? 0 : a == "y" ? 1 : a == "z" ? 2 : -2;
    if (st.symmetry_axis == -2) fail_at(ctx, "symmetry", "must be one of x, y, z, none");
  }
  if (b.contains("invert")) {
    if (!b["invert"].is_boolean()) fail_at(ctx, "invert", "must be true or false");
    st.invert = b["invert"].get<bool>();
  }
  if (b.contains("detail")) {
    const json& v = b["detail"];
    if (!v.is_number() || !(v.get<double>() >= 0) || !std::isfinite(v.get<double>()))
      fail_at(ctx, "detail", "must be a non-negative length (edge length for this stroke; 0: the session's detail)");
    st.detail = v.get<double>();
  }
  if (b.contains("falloff")) {  // absent: smooth, the curve of every stroke recorded before presets
    const json& v = b["falloff"];
    const auto f = v.is_string() ? deform::parse_brush_falloff(v.get<std::string>()) : std::nullopt;
    if (!f) fail_at(ctx, "falloff", std::string("must be one of ") + deform::brush_falloff_list());
    st.falloff = *f;
  }
  return st;
}

MaskOp parse_mask_op(const json& m, const std::string& ctx, bool stroke) {
  if (!m.is_object()) throw std::invalid_argument(ctx + "must be an object");
  if (!m.contains("op")) fail_at(ctx, "op", "is missing");
  const auto kind = m["op"].is_string() ? parse_mask_op_kind(m["op"].get<std::string>()) : std::nullopt;
  if (!kind) fail_at(ctx, "op", std::string("must be one of ") + mask_op_list());
  MaskOp op;
  op.kind = *kind;
  if (stroke && !mask_op_has_path(op.kind)) fail_at(ctx, "op", "must be paint or erase for a stroke");
  if (!mask_op_has_path(op.kind)) {
    check_keys(m, ctx, {"op"});
    return op;
  }
  if (stroke) {
    check_keys(m, ctx, {"op", "radius", "strength"});
  } else {
    check_keys(m, ctx, {"op", "path", "radius", "strength"});
    op.path = parse_path(m, ctx);
  }
  if (!m.contains("radius")) fail_at(ctx, "radius", "is missing");
  op.radius = positive_number(m["radius"], ctx, "radius");
  if (m.contains("strength")) {
    const json& v = m["strength"];
    if (!v.is_number() || !(v.get<double>() >= 0 && v.get<double>() <= 1)) fail_at(ctx, "strength", "must be a number between 0 and 1");
    op.strength = v.get<double>();
  }
  return op;
}

json to_json(const MaskOp& op) {
  json j = {{"op", mask_op_name(op.kind)}};
  if (mask_op_has_path(op.kind)) {
    j["path"] = path_json(op.path);
    j["radius"] = op.radius;
    j["strength"] = op.strength;
  }
  return j;
}

SettingsPatch parse_settings(const json& s, const std::string& ctx) {
  if (!s.is_object()) throw std::invalid_argument(ctx + "must be an object");
  check_keys(s, ctx, {"epsilon", "min_length", "max_length", "features", "guard_crossings"});
  SettingsPatch p;
  if (s.contains("epsilon")) p.epsilon = length(s["epsilon"], ctx, "epsilon");
  if (s.contains("min_length")) p.min_length = length(s["min_length"], ctx, "min_length");
  if (s.contains("max_length")) p.max_length = length(s["max_length"], ctx, "max_length");
  if (s.contains("features")) {
    const json& f = s["features"];
    if (!f.is_number() || !std::isfinite(f.get<double>()) || f.get<double>() < 0 || f.get<double>() > 180)
      fail_at(ctx, "features", "must be an angle in degrees between 0 and 180");
    p.features = f.get<double>();
  }
  if (s.contains("guard_crossings")) {
    if (!s["guard_crossings"].is_boolean()) fail_at(ctx, "guard_crossings", "must be true or false");
    p.guard_crossings = s["guard_crossings"].get<bool>();
  }
  return p;
}

json to_json(const SettingsPatch& s) {
  json j = json::object();
  auto put = [&](const char* k, const std::optional<LengthSetting>& v) {
    if (!v) return;
    if (v->percent) {
      json num = v->value;
      j[k] = num.dump() + "%";
    } else {
      j[k] = v->value;
    }
  };
  put("epsilon", s.epsilon);
  put("min_length", s.min_length);
  put("max_length", s.max_length);
  if (s.features) j["features"] = *s.features;
  if (s.guard_crossings) j["guard_crossings"] = *s.guard_crossings;
  return j;
}

deform::HandleTransform GrabStep::total_at(double f) const {
  deform::HandleTransform t;
  t.translation = f * translate;
  t.rotation = deform::angle_axis(f * degrees * (M_PI / 180.0), axis);
  t.scale = 1.0 + f * (scale - 1.0);
  return t;
}

SessionFile parse_session_file(const json& j) {
  if (!j.is_object()) throw std::invalid_argument("session file: must be a JSON object");
  check_keys(j, "session file: ", {"version", "settings", "steps"});
  if (!j.contains("version") || !j["version"].is_number_integer() || j["version"].get<long long>() != 1)
    throw std::invalid_argument("session file: 'version' must be 1");
  SessionFile f;
  if (j.contains("settings")) f.settings = parse_settings(j["settings"]);
  if (!j.contains("steps") || !j["steps"].is_array())
    throw std::invalid_argument("session file: 'steps' must be an array");
  int i = 0;
  for (const json& s : j["steps"]) {
    ++i;
    const std::string at = "step " + std::to_string(i);
    if (!s.is_object() || s.size() != 1)
      throw std::invalid_argument(at + ": must be an object with one key: grab, brush, remesh, mask, undo or redo");
    const std::string kind = s.begin().key();
    const json& v = s.begin().value();
    const std::string ctx = at + " (" + kind + "): ";
    SessionStep step;
    if (kind == "grab") {
      step.kind = SessionStep::Kind::Grab;
      step.grab = parse_grab(v, ctx);
    } else if (kind == "brush") {
      step.kind = SessionStep::Kind::Brush;
      step.brush = parse_brush(v, ctx);
    } else if (kind == "remesh") {
      step.kind = SessionStep::Kind::Remesh;
      if (!v.is_object()) throw std::invalid_argument(ctx + "must be an object {\"iterations\": k}");
      check_keys(v, ctx, {"iterations", "detail"});
      if (!v.contains("iterations")) fail_at(ctx, "iterations", "is missing");
      step.count = positive_int(v["iterations"], ctx, "iterations");
      if (v.contains("detail")) step.detail = positive_number(v["detail"], ctx, "detail", true);
    } else if (kind == "mask") {
      step.kind = SessionStep::Kind::Mask;
      step.mask = parse_mask_op(v, ctx);
    } else if (kind == "undo" || kind == "redo") {
      step.kind = kind == "undo" ? SessionStep::Kind::Undo : SessionStep::Kind::Redo;
      step.count = positive_int(v, ctx, kind);
    } else {
      throw std::invalid_argument(at + ": unknown step '" + kind + "' (expected grab, brush, remesh, mask, undo or redo)");
    }
    f.steps.push_back(step);
  }
  return f;
}

SessionFile parse_session_file(const std::string& text) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    // parse_error, and out_of_range for numbers beyond double ("1e400").
    throw std::invalid_argument(std::string("session file: not valid JSON: ") + e.what());
  }
  return parse_session_file(j);
}

json to_json(const SessionFile& f) {
  json steps = json::array();
  for (const SessionStep& s : f.steps) {
    switch (s.kind) {
      case SessionStep::Kind::Grab: {
        const GrabStep& g = s.grab;
        json grab = {{"center", {g.center.x, g.center.y, g.center.z}},
                     {"handle_radius", g.handle_radius},
                     {"roi_radius", g.roi_radius},
                     {"translate", {g.translate.x, g.translate.y, g.translate.z}},
                     {"rotate", {{"axis", {g.axis.x, g.axis.y, g.axis.z}}, {"degrees", g.degrees}}},
                     {"scale", g.scale},
                     {"substeps", g.substeps}};
        steps.push_back({{"grab", grab}});
        break;
      }
      case SessionStep::Kind::Brush: {
        const deform::BrushSettings& st = s.brush.settings;
        json brush = {{"tool", deform::brush_tool_name(st.tool)},
                      {"path", path_json(s.brush.path)},
                      {"radius", st.radius},
                      {"strength", st.strength},
                      {"spacing", st.spacing},
                      {"symmetry", st.symmetry_axis < 0 ? "none" : kAxes[st.symmetry_axis]},
                      {"invert", st.invert}};
        if (st.detail > 0) brush["detail"] = st.detail;
        if (st.falloff != deform::BrushFalloff::Smooth) brush["falloff"] = deform::brush_falloff_name(st.falloff);
        if (!s.brush.pressure.empty()) brush["pressure"] = s.brush.pressure;
        steps.push_back({{"brush", brush}});
        break;
      }
      case SessionStep::Kind::Remesh: {
        json remesh = {{"iterations", s.count}};
        if (s.detail > 0) remesh["detail"] = s.detail;
        steps.push_back({{"remesh", remesh}});
        break;
      }
      case SessionStep::Kind::Mask:
        steps.push_back({{"mask", to_json(s.mask)}});
        break;
      case SessionStep::Kind::Undo:
        steps.push_back({{"undo", s.count}});
        break;
      case SessionStep::Kind::Redo:
        steps.push_back({{"redo", s.count}});
        break;
    }
  }
  return {{"version", 1}, {"settings", to_json(f.settings)}, {"steps", steps}};
}

}  // namespace adasculpt::sculpt
