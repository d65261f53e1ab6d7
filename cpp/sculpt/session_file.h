#pragma once
// Session files: a replayable sculpting session, shared by the CLI (`adasculpt replay`), the wasm
// module and the browser app.
//
//   {"version": 1,
//    "settings": {"epsilon": 0.001 | "0.05%", "min_length": ..., "max_length": ..., "features": 45},
//    "steps": [
//      {"grab": {"center": [x,y,z], "handle_radius": r, "roi_radius": R,
//                "translate": [dx,dy,dz], "rotate": {"axis": [ax,ay,az], "degrees": a},
//                "scale": s, "substeps": n}},
//      {"brush": {"tool": "inflate", "path": [[x,y,z], ...], "radius": r, "strength": s,
//                 "symmetry": "x", "spacing": f, "invert": false, "pressure": [p, ...],
//                 "detail": L, "falloff": "sharp"}},
//      {"remesh": {"iterations": k, "detail": L}},
//      {"mask": {"op": "paint", "path": [[x,y,z], ...], "radius": r, "strength": s}},
//      {"mask": {"op": "invert"}},
//      {"undo": n}, {"redo": n}]}
//
// A grab picks the surface point closest to `center` and applies the total transform gradually
// over `substeps` frames (frame i applies the fraction i/n of the translation, of the rotation
// angle and of the scale change); translate, rotate, scale and substeps are optional (identity,
// substeps 1). Lengths in settings are absolute or, as strings ending in '%', percent of the
// bounding-box diagonal. A brush stroke needs tool, path and radius (absolute); strength defaults
// to 0.5, spacing to 0.25 (of the radius), symmetry to "none", pressure to 1 per path point,
// falloff to "smooth" (smooth, sphere, sharp, linear, constant: deform/brushes.h), detail to 0 (the
// session's settings; > 0: an absolute edge length for this stroke). A remesh step's detail > 0
// remeshes the whole mesh to that constant edge length (Session::remesh; the detail flood fill).
//
// A mask step's op is one of paint, erase, clear, fill, invert, blur, sharpen (sculpt/mask.h);
// paint and erase need path and radius, strength defaults to 1.
//
// Every validation error is a std::invalid_argument with one line naming the step and field:
//   "step 3 (grab): 'roi_radius' must be a positive number".
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "deform/handle_transform.h"
#include "mesh/types.h"
#include "remesh/length_spec.h"
#include "sculpt/brush.h"
#include "sculpt/mask.h"

namespace adasculpt::sculpt {

// A length setting as written: absolute, or percent of the bounding-box diagonal.
using LengthSetting = remesh::LengthSpec;

// The keys present in a "settings" object (absent keys stay empty).
struct SettingsPatch {
  std::optional<LengthSetting> epsilon, min_length, max_length;
  std::optional<double> features;  // degrees, 0 = off
  // Sculpting's remeshing checks that it creates no crossing triangles (Remesher::
  // set_region_crossing_guard): safer pinches and creases, frames about 1.6x the cost.
  std::optional<bool> guard_crossings;
};
// Throws std::invalid_argument "<context>'epsilon' must be ..." (context e.g. "settings: ").
SettingsPatch parse_settings(const nlohmann::json& s, const std::string& context = "settings: ");
nlohmann::json to_json(const SettingsPatch& s);

// The settings of a brush stroke (tool, radius, strength, spacing, symmetry, invert, detail,
// falloff), checked as in a brush step; `stroke_keys` are further keys the caller reads itself (a
// step's path, pressure). Also what the wasm module's brushBegin takes.
deform::BrushSettings parse_brush_settings(const nlohmann::json& b, const std::string& context = "brush: ",
                                           std::initializer_list<const char*> stroke_keys = {});

struct GrabStep {
  Point center{0.0};
  double handle_radius = 0, roi_radius = 0;
  Vec3 translate{0.0};
  Vec3 axis{0.0, 0.0, 1.0};
  double degrees = 0;
  double scale = 1;
  int substeps = 1;
  // The total transform after the fraction f in [0,1] of the grab.
  deform::HandleTransform total_at(double f) const;
};

struct SessionStep {
  enum class Kind { Grab, Brush, Remesh, Undo, Redo, Mask } kind = Kind::Grab;
  GrabStep grab;  // Kind::Grab
  int count = 1;  // remesh iterations, undo / redo count
  BrushStroke brush;  // Kind::Brush (last: {kind, grab, count} aggregate initialisers stay valid)
  double detail = 0;  // Kind::Remesh: > 0, a constant edge length instead of the settings
  MaskOp mask;        // Kind::Mask
};

// A mask operation as in a mask step (also what the wasm module's mask() takes); checked. With
// `stroke`, a paint or erase without its path (the wasm module's maskBegin).
MaskOp parse_mask_op(const nlohmann::json& m, const std::string& context = "mask: ", bool stroke = false);
nlohmann::json to_json(const MaskOp& op);

struct SessionFile {
  SettingsPatch settings;
  std::vector<SessionStep> steps;
};

SessionFile parse_session_file(const nlohmann::json& j);
// Parses JSON text first; a syntax error becomes std::invalid_argument too.
SessionFile parse_session_file(const std::string& text);
nlohmann::json to_json(const SessionFile& f);

}  // namespace adasculpt::sculpt
