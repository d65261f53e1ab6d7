// embind bindings: Module.Session, a thin shell over sculpt::Session plus the RenderBuffers the
// page draws from. Converts typed arrays and plain objects; no logic of its own.
//
// One convention for JavaScript: plain objects in and out with camelCase keys. The core speaks
// nlohmann::json with snake_case keys (session files, the CLI's --json); to_js()/from_js() below
// convert between the two, renaming keys (min_length <-> minLength). Session files themselves are a
// file format shared with the CLI: replay() takes them as written (text or parsed object).
//
// Errors: a C++ exception is caught here, its message stored in a static slot, and the method
// returns a neutral value; a JS wrapper installed on Module.Session.prototype (on first
// construction, when every type is registered) sees the flag and throws `new Error(message)`.
// Throwing a JS exception from inside C++ frames would skip their destructors (leaks); this way
// every C++ frame has returned normally before JS throws, and no extra wasm call is needed.
//
// One wasm call per frame: grabDrag() (brushStamp() while brushing) does the whole frame (deform,
// remesh, render-buffer update) and returns the changes with pointers into wasm memory, so the page
// builds its typed-array views itself (views must be rebuilt after every call anyway: memory growth
// detaches them).
#include <emscripten/bind.h>
#include <emscripten/em_js.h>
#include <emscripten/emscripten.h>
#include <emscripten/val.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <optional>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "geometry/quality.h"
#include "mesh/build_from_triangles.h"
#include "remesh/length_spec.h"
#include "remesh/remesher.h"
#include "sculpt/render_buffers.h"
#include "sculpt/session.h"
#include "sculpt/session_file.h"

// Wraps every method of Module.Session so that a recorded C++ error becomes a thrown Error.
// clang-format off
EM_JS(void, install_error_wrappers_js, (int* flag_address, const char* message), {
  var proto = Module['Session'].prototype;
  if (proto.__adasculptErrors) return;
  proto.__adasculptErrors = true;
  var flag = flag_address >> 2;
  Object.getOwnPropertyNames(proto).forEach(function (name) {
    var raw = proto[name];
    if (name === 'constructor' || typeof raw !== 'function') return;
    proto[name] = function () {
      var result = raw.apply(this, arguments);
      if (HEAP32[flag]) {
        HEAP32[flag] = 0;
        throw new Error(UTF8ToString(message));
      }
      return result;
    };
  });
});
// clang-format on

namespace adasculpt::bindings {

using emscripten::val;

namespace {

struct ErrorSlot {
  int flag = 0;
  char message[4096] = {0};
};
ErrorSlot g_error;

void set_error(const char* msg) {
  std::snprintf(g_error.message, sizeof g_error.message, "%s", msg);
  g_error.flag = 1;
}

// Runs f; on a C++ exception records its message and returns `fallback`.
template <class R, class F>
R guarded(R fallback, F&& f) {
  try {
    return f();
  } catch (const std::exception& e) {
    set_error(e.what());
  } catch (...) {
    set_error("unknown C++ exception");
  }
  return fallback;
}
template <class F>
void guarded_void(F&& f) {
  guarded(0, [&] {
    f();
    return 0;
  });
}

// Copies a Uint8Array/ArrayBuffer/typed array `src` into a std::vector of T (converting element type).
template <class T>
std::vector<T> copy_typed_array(const val& src, const char* view_type) {
  val arr = src.instanceof(val::global("ArrayBuffer")) ? val::global(view_type).new_(src) : src;
  size_t n = arr["length"].as<size_t>();
  std::vector<T> out(n);
  // The view is taken after the allocation, which may have grown (and detached) wasm memory.
  val(emscripten::typed_memory_view(n, out.data())).call<void>("set", arr);
  return out;
}

io::Format parse_format(std::string f) {
  std::transform(f.begin(), f.end(), f.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (f == "obj") return io::Format::OBJ;
  if (f == "stl") return io::Format::STL;
  if (f == "ply") return io::Format::PLY;
  if (f == "off") return io::Format::OFF;
  throw std::invalid_argument("unknown export format '" + f + "' (use obj, stl, ply or off)");
}

// "min_angle_deg" -> "minAngleDeg"; "minLength" -> "min_length".
std::string camel_case(const std::string& k) {
  std::string out;
  bool upper = false;
  for (char c : k) {
    if (c == '_') {
      upper = !out.empty();
      continue;
    }
    out += upper ? char(std::toupper(static_cast<unsigned char>(c))) : c;
    upper = false;
  }
  return out;
}
std::string snake_case(const std::string& k) {
  std::string out;
  for (char c : k) {
    if (std::isupper(static_cast<unsigned char>(c))) {
      out += '_';
      out += char(std::tolower(static_cast<unsigned char>(c)));
    } else {
      out += c;
    }
  }
  return out;
}

// The core's JSON as a plain JS value, object keys in camelCase.
val to_js(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::object: {
      val o = val::object();
      for (auto it = j.begin(); it != j.end(); ++it) o.set(camel_case(it.key()), to_js(it.value()));
      return o;
    }
    case nlohmann::json::value_t::array: {
      val a = val::array();
      for (const auto& x : j) a.call<void>("push", to_js(x));
      return a;
    }
    case nlohmann::json::value_t::string: return val(j.get<std::string>());
    case nlohmann::json::value_t::boolean: return val(j.get<bool>());
    case nlohmann::json::value_t::number_integer:
    case nlohmann::json::value_t::number_unsigned:
    case nlohmann::json::value_t::number_float: return val(j.get<double>());
    default: return val::null();
  }
}

// A plain JS value as the core's JSON; object keys to snake_case when `snake`. Throws on values
// JSON has no place for (functions, symbols, cycles are not followed: depth-limited).
nlohmann::json from_js(const val& v, bool snake, int depth = 0) {
  if (depth > 64) throw std::invalid_argument("object nested too deeply");
  const std::string type = v.typeOf().as<std::string>();
  if (type == "undefined" || v.isNull()) return nullptr;
  if (type == "boolean") return v.as<bool>();
  if (type == "number") {  // integral numbers stay integers (a session file's "version": 1, counts)
    const double d = v.as<double>();
    if (std::floor(d) == d && std::fabs(d) < 9e15) return static_cast<std::int64_t>(d);
    return d;
  }
  if (type == "string") return v.as<std::string>();
  if (type != "object") throw std::invalid_argument("expected plain values, got a " + type);
  if (val::global("Array").call<bool>("isArray", v)) {
    nlohmann::json a = nlohmann::json::array();
    const size_t n = v["length"].as<size_t>();
    for (size_t i = 0; i < n; ++i) a.push_back(from_js(v[i], snake, depth + 1));
    return a;
  }
  if (val::global("ArrayBuffer").call<bool>("isView", v)) {
    nlohmann::json a = nlohmann::json::array();
    for (double x : copy_typed_array<double>(v, "Float64Array")) a.push_back(x);
    return a;
  }
  nlohmann::json o = nlohmann::json::object();
  const val keys = val::global("Object").call<val>("keys", v);
  const size_t n = keys["length"].as<size_t>();
  for (size_t i = 0; i < n; ++i) {
    const std::string k = keys[i].as<std::string>();
    const val x = v[k];
    if (x.isUndefined()) continue;
    o[snake ? snake_case(k) : k] = from_js(x, snake, depth + 1);
  }
  return o;
}

// A plain object argument (not null, not an array), else std::invalid_argument naming the method.
nlohmann::json object_arg(const val& v, const char* method, bool snake) {
  const bool ok = v.typeOf().as<std::string>() == "object" && !v.isNull() &&
                  !val::global("Array").call<bool>("isArray", v);
  if (!ok) throw std::invalid_argument(std::string(method) + ": expected a plain object");
  return from_js(v, snake);
}

}  // namespace

class SessionHandle {
 public:
  SessionHandle() { install_error_wrappers_js(&g_error.flag, g_error.message); }

  bool has_mesh() const { return session_.has_mesh(); }

  void load_bytes(const val& bytes, const std::string& name_hint) {
    guarded_void([&] {
      std::vector<std::uint8_t> data = copy_typed_array<std::uint8_t>(bytes, "Uint8Array");
      session_.load_bytes(data.data(), data.size(), name_hint);
      sync(true);
    });
  }

  void load_arrays(const val& positions, const val& indices) {
    guarded_void([&] {
      std::vector<double> p = copy_typed_array<double>(positions, "Float64Array");
      std::vector<std::uint32_t> t = copy_typed_array<std::uint32_t>(indices, "Uint32Array");
      if (p.size() % 3 != 0) throw std::invalid_argument("positions: length must be a multiple of 3");
      if (t.size() % 3 != 0) throw std::invalid_argument("indices: length must be a multiple of 3");
      std::vector<std::array<double, 3>> points(p.size() / 3);
      std::vector<std::array<std::uint32_t, 3>> tris(t.size() / 3);
      std::copy(p.begin(), p.end(), points.empty() ? nullptr : points[0].data());
      std::copy(t.begin(), t.end(), tris.empty() ? nullptr : tris[0].data());
      mesh::BuildReport report;
      mesh::SurfaceMesh m = mesh::build_from_triangles(points, tris, &report);
      session_.load(std::move(m), std::move(report.warnings));
      sync(true);
    });
  }

  // The repairs of the last load, one sentence each (Session::load_warnings).
  val load_warnings() const {
    val out = val::array();
    for (const std::string& w : session_.load_warnings()) out.call<void>("push", w);
    return out;
  }

  // {epsilon, minLength, maxLength, features}: numbers are absolute, "0.05%" strings percent of the
  // diagonal; keys not given keep their value. settings() answers in absolute lengths plus diagonal.
  void set_settings(const val& settings) {
    guarded_void([&] { session_.set_settings(object_arg(settings, "setSettings", true)); });
  }
  val settings() const {
    return guarded(val::null(), [&] { return to_js(session_.settings()); });
  }

  val pick(double ox, double oy, double oz, double dx, double dy, double dz) const {
    return guarded(val::null(), [&] {
      Point hit(0.0);
      bool ok = session_.has_mesh() && session_.pick(Point(ox, oy, oz), Vec3(dx, dy, dz), &hit);
      val r = val::object();
      r.set("hit", ok);
      r.set("x", hit.x);
      r.set("y", hit.y);
      r.set("z", hit.z);
      return r;
    });
  }

  void grab_begin(double cx, double cy, double cz, double handle_radius, double roi_radius) {
    guarded_void([&] {
      session_.grab_begin(Point(cx, cy, cz), handle_radius, roi_radius);
      sync(false);
    });
  }

  // The whole frame; returns changes() so the page needs no second call.
  val grab_drag(double tx, double ty, double tz, double ax, double ay, double az, double degrees, double scale) {
    return guarded(val::null(), [&] {
      deform::HandleTransform t;
      t.translation = glm::dvec3(tx, ty, tz);
      glm::dvec3 axis(ax, ay, az);
      double len = glm::length(axis);
      if (degrees != 0.0 && len > 0.0) t.rotation = deform::angle_axis(degrees * (M_PI / 180.0), axis / len);
      t.scale = scale;
      session_.grab_drag(t);
      sync(false);
      return changes();
    });
  }

  void grab_end() {
    guarded_void([&] {
      session_.grab_end();
      // Incremental: a stroke's end compacts the mesh only once deleted slots add up, and then the
      // session reports everything changed (a full rebuild took 3-4 ms per stroke on the bunny).
      sync(false);
    });
  }
  bool grabbing() const { return session_.grabbing(); }

  // A brush stroke (sculpt/brush.h): brushBegin(settings), one brushStamp(samples) per animation
  // frame, brushEnd(); the stroke is one undo step. Settings: a plain object
  // {tool, radius, strength, spacing, symmetry, invert, detail, falloff} (absolute lengths), checked
  // like a session file's brush step.
  void brush_begin(const val& settings) {
    guarded_void([&] {
      session_.brush_begin(sculpt::parse_brush_settings(object_arg(settings, "brushBegin", true)));
      sync(false);
    });
  }

  // The frame's pointer samples as one array [x, y, z, pressure, x, y, z, pressure, ...] (surface
  // points; for the grab brush, the pointer in space), so coalesced pointer events cost one call.
  // Returns changes() with the timings summed over the samples.
  val brush_stamp(const val& samples) {
    return guarded(val::null(), [&] {
      const std::vector<double> s = copy_typed_array<double>(samples, "Float64Array");
      if (s.empty() || s.size() % 4 != 0)
        throw std::invalid_argument("brushStamp: expected x, y, z, pressure for each of at least one sample");
      sculpt::FrameTimings sum;
      for (size_t i = 0; i < s.size(); i += 4) {
        try {
          session_.brush_stamp(Point(s[i], s[i + 1], s[i + 2]), s[i + 3]);
        } catch (...) {
          sync(false);  // the stamps before the error changed the mesh: keep the page in step
          throw;
        }
        const sculpt::FrameTimings& t = session_.last_frame();
        sum.roi_ms += t.roi_ms;
        sum.deform_ms += t.deform_ms;
        sum.remesh_ms += t.remesh_ms;
        sum.total_ms += t.total_ms;
        sum.stamps += t.stamps;
      }
      sync(false);
      return changes_with(sum);
    });
  }

  void brush_end() {
    guarded_void([&] {
      session_.brush_end();
      sync(false);  // as grab_end
    });
  }
  bool brushing() const { return session_.brushing(); }

  // Masking (sculpt/mask.h), each call one undo step: mask({op: 'invert'}), mask({op: 'paint',
  // path: [[x, y, z], ...], radius, strength}); a stroke as the pointer moves: maskBegin({op:
  // 'paint' | 'erase', radius, strength}), maskStamp([x, y, z, x, y, z, ...]) per frame, maskEnd().
  // mask() and maskStamp() return changes() (as brushStamp); the values are maskValues().
  val mask(const val& op) {
    return guarded(val::null(), [&] {
      session_.mask(sculpt::parse_mask_op(object_arg(op, "mask", true)));
      sync(false);
      return changes();
    });
  }
  void mask_begin(const val& op) {
    guarded_void([&] {
      session_.mask_begin(sculpt::parse_mask_op(object_arg(op, "maskBegin", true), "mask: ", true));
      sync(false);
    });
  }
  val mask_stamp(const val& points) {
    return guarded(val::null(), [&] {
      const std::vector<double> p = copy_typed_array<double>(points, "Float64Array");
      if (p.empty() || p.size() % 3 != 0) throw std::invalid_argument("maskStamp: expected x, y, z for each of at least one point");
      try {
        for (size_t i = 0; i < p.size(); i += 3) session_.mask_stamp(Point(p[i], p[i + 1], p[i + 2]));
      } catch (...) {
        sync(false);
        throw;
      }
      sync(false);
      return changes();
    });
  }
  void mask_end() {
    guarded_void([&] {
      session_.mask_end();
      sync(false);
    });
  }
  bool masking() const { return session_.masking(); }

  // detail > 0: every edge towards that absolute length (the detail flood fill); 0: the settings.
  void remesh_detail(int iterations, double detail) {
    guarded_void([&] {
      session_.remesh(iterations, detail);
      sync(true);
    });
  }
  void remesh(int iterations) { remesh_detail(iterations, 0); }
  bool undo() {
    return guarded(false, [&] {
      bool ok = session_.undo();
      sync(false);  // the change set says what the step touched (everything for a whole-mesh step)
      return ok;
    });
  }
  bool redo() {
    return guarded(false, [&] {
      bool ok = session_.redo();
      sync(false);
      return ok;
    });
  }
  bool can_undo() const { return session_.can_undo(); }
  bool can_redo() const { return session_.can_redo(); }

  // A session file (sculpt/session_file.h) as its text or as the parsed object, keys as in the file;
  // returns the report (`adasculpt replay --json`'s object, keys in camelCase).
  val replay(const val& file) {
    return guarded(val::null(), [&] {
      const nlohmann::json j = file.typeOf().as<std::string>() == "string"
                                   ? nlohmann::json::parse(file.as<std::string>())
                                   : object_arg(file, "replay", false);
      val out = to_js(session_.replay(j));
      sync(true);
      return out;
    });
  }

  // Quality of the whole mesh (O(n): not for every frame: minAngleDeg, meanMinAngleDeg, vertices,
  // faces, valenceHistogram, ...), the last frame's timings and the history flags.
  val stats() const {
    return guarded(val::null(), [&] {
      nlohmann::json j = nlohmann::json::object();
      if (session_.has_mesh()) j = geometry::to_json(session_.quality());
      return to_js(with_frame_and_history(j));
    });
  }
  // The same keys for what a viewer shows after every stroke, kept up to date from the changes
  // (Session::quick_quality: vertices, faces, edges, min/max angle, mean min angle, shares under 30
  // and 10 degrees; costs what changed, not the mesh). The other quality keys are 0.
  val quick_stats() const {
    return guarded(val::null(), [&] {
      nlohmann::json j = nlohmann::json::object();
      if (session_.has_mesh()) j = geometry::to_json(session_.quick_quality());
      return to_js(with_frame_and_history(j));
    });
  }

 private:
  nlohmann::json& with_frame_and_history(nlohmann::json& j) const {
    const sculpt::FrameTimings& t = session_.last_frame();
    j["last_frame"] = {{"roi_ms", t.roi_ms},       {"field_ms", t.field_ms},   {"refine_ms", t.refine_ms},
                       {"deform_ms", t.deform_ms}, {"remesh_ms", t.remesh_ms}, {"total_ms", t.total_ms}};
    j["can_undo"] = session_.can_undo();
    j["can_redo"] = session_.can_redo();
    if (!session_.remesh_warning().empty()) j["warning"] = session_.remesh_warning();  // last remesh hit its limit
    return j;
  }

 public:
  val export_mesh(const std::string& format) const {
    return guarded(val::null(), [&] {
      std::vector<std::uint8_t> bytes = session_.export_bytes(parse_format(format));
      return val(emscripten::typed_memory_view(bytes.size(), bytes.data())).call<val>("slice");
    });
  }

  // Autosave (web/autosave.js): the whole state as one Uint8Array (sculpt::Session::save_state,
  // history within max_history_bytes), then the changes since as small records (save_changes:
  // null when a whole state is due), and back, with the records in
  // order: restoreSaved(state, records) (restoreState(state): none); memoryBytes() for the load-size check.
  val save_state(double max_history_bytes) {
    return guarded(val::null(), [&] {
      std::vector<std::uint8_t> bytes = session_.save_state(size_t(std::max(0.0, max_history_bytes)));
      return val(emscripten::typed_memory_view(bytes.size(), bytes.data())).call<val>("slice");
    });
  }
  val save_changes() {
    return guarded(val::null(), [&] {
      std::optional<std::vector<std::uint8_t>> bytes = session_.save_changes();
      if (!bytes) return val::null();
      return val(emscripten::typed_memory_view(bytes->size(), bytes->data())).call<val>("slice");
    });
  }
  void restore_state(const val& bytes) { restore_state_with(bytes, val::array()); }
  void restore_state_with(const val& bytes, const val& changes) {
    guarded_void([&] {
      std::vector<std::uint8_t> data = copy_typed_array<std::uint8_t>(bytes, "Uint8Array");
      std::vector<std::vector<std::uint8_t>> records;
      const unsigned n = changes.isUndefined() || changes.isNull() ? 0 : changes["length"].as<unsigned>();
      for (unsigned i = 0; i < n; ++i) records.push_back(copy_typed_array<std::uint8_t>(changes[i], "Uint8Array"));
      std::vector<sculpt::Session::ByteSpan> spans;
      for (const auto& r : records) spans.push_back({r.data(), r.size()});
      session_.restore_state(data.data(), data.size(), spans);
      sync(true);
    });
  }
  double memory_bytes() const { return double(session_.memory_bytes()); }

  val positions() const { return float_view(buffers_.positions(), buffers_.vertex_count()); }
  val normals() const { return float_view(buffers_.normals(), buffers_.vertex_count()); }
  // One mask value per vertex slot (0 where unmasked), a view like positions().
  val mask_values() const {
    return val(emscripten::typed_memory_view(size_t(buffers_.vertex_count()), buffers_.masks()));
  }
  val indices() const {
    return val(emscripten::typed_memory_view(3 * size_t(buffers_.face_count()), buffers_.indices()));
  }

  // The render changes accumulated since the last changes() (or grabDrag()), plus where the
  // buffers are (byte addresses into wasm memory) and the last frame's core timings.
  val changes() { return changes_with(session_.last_frame()); }

 private:
  val changes_with(const sculpt::FrameTimings& t) {
    sculpt::RenderChanges c = buffers_.take_pending();
    val r = val::object();
    r.set("reallocated", c.reallocated);
    r.set("indicesChanged", c.indices_changed);
    r.set("vertexBegin", c.vertex_begin);
    r.set("vertexEnd", c.vertex_end);
    r.set("faceBegin", c.face_begin);
    r.set("faceEnd", c.face_end);
    r.set("vertexCount", c.vertex_count);
    r.set("faceCount", c.face_count);
    // The box of the positions written ([minX, minY, minZ, maxX, maxY, maxZ]; null when none was)
    // and whether they were all of them: the viewer's bounds without a pass over the vertices.
    r.set("rebuilt", c.rebuilt);
    if (c.box_min[0] <= c.box_max[0]) {
      val box = val::array();
      for (int k = 0; k < 3; ++k) box.call<void>("push", c.box_min[k]);
      for (int k = 0; k < 3; ++k) box.call<void>("push", c.box_max[k]);
      r.set("box", box);
    } else {
      r.set("box", val::null());
    }
    r.set("vertices", double(session_.has_mesh() ? session_.mesh().n_vertices() : 0));
    r.set("faces", double(session_.has_mesh() ? session_.mesh().n_faces() : 0));
    r.set("vertexCapacity", double(buffers_.vertex_capacity()));
    r.set("faceCapacity", double(buffers_.face_capacity()));
    r.set("positionsPtr", reinterpret_cast<std::uintptr_t>(buffers_.positions()));
    r.set("normalsPtr", reinterpret_cast<std::uintptr_t>(buffers_.normals()));
    r.set("masksPtr", reinterpret_cast<std::uintptr_t>(buffers_.masks()));
    r.set("indicesPtr", reinterpret_cast<std::uintptr_t>(buffers_.indices()));
    // The face slots whose triangle changed (web/slot-ray-tree.js refits only those), valid until
    // the next changes(); allFacesDirty instead after a rebuild or a reallocation.
    r.set("allFacesDirty", buffers_.all_faces_dirty());
    r.set("dirtyFacesPtr", reinterpret_cast<std::uintptr_t>(buffers_.dirty_faces()));
    r.set("dirtyFaceCount", double(buffers_.dirty_face_count()));
    val ms = val::object();
    ms.set("roi", t.roi_ms);
    ms.set("field", t.field_ms);
    ms.set("refine", t.refine_ms);
    ms.set("deform", t.deform_ms);
    ms.set("remesh", t.remesh_ms);
    ms.set("total", t.total_ms);
    ms.set("buffers", buffers_ms_);
    ms.set("stamps", t.stamps);
    ms.set("roiCapped", t.roi_capped);  // the grab's ROI was cut to its vertex budget
    ms.set("roiVertices", t.roi_vertices);
    ms.set("remeshedVertices", t.remeshed_vertices);  // the grab frame's remeshing scope (what it strained)
    ms.set("fieldRefreshed", t.field_refreshed);       // the grab frame applied a finished field solve
    r.set("timings", ms);
    return r;
  }

  static val float_view(const float* p, std::uint32_t vertices) {
    return val(emscripten::typed_memory_view(3 * size_t(vertices), p));
  }

  // Brings the render buffers up to date with what the session changed.
  void sync(bool everything) {
    if (!session_.has_mesh()) return;
    const double t0 = emscripten_get_now();
    const sculpt::ChangeSet& c = session_.changes();
    if (everything) {
      buffers_.rebuild(session_.mesh());
    } else {
      buffers_.update(session_.mesh(), c);
    }
    session_.clear_changes();
    buffers_ms_ = emscripten_get_now() - t0;
  }

  sculpt::Session session_;
  sculpt::RenderBuffers buffers_;
  double buffers_ms_ = 0;  // time of the last render-buffer update (part of the frame, after the core)
};

// Module.defaultSettings(): what a new session starts with, {epsilon: "0.05%", minLength, maxLength,
// features}, from the core's constants (the web app shows these before a mesh is loaded).
val default_settings() {
  val o = val::object();
  o.set("epsilon", remesh::percent_text(remesh::kDefaultEpsilonPct));
  o.set("minLength", remesh::percent_text(remesh::kDefaultMinLengthPct));
  o.set("maxLength", remesh::percent_text(remesh::kDefaultMaxLengthPct));
  o.set("features", 0);
  return o;
}

EMSCRIPTEN_BINDINGS(adasculpt) {
  emscripten::function("defaultSettings", &default_settings);
  emscripten::class_<SessionHandle>("Session")
      .constructor<>()
      .function("hasMesh", &SessionHandle::has_mesh)
      .function("loadBytes", &SessionHandle::load_bytes)
      .function("loadArrays", &SessionHandle::load_arrays)
      .function("loadWarnings", &SessionHandle::load_warnings)
      .function("setSettings", &SessionHandle::set_settings)
      .function("settings", &SessionHandle::settings)
      .function("pick", &SessionHandle::pick)
      .function("grabBegin", &SessionHandle::grab_begin)
      .function("grabDrag", &SessionHandle::grab_drag)
      .function("grabEnd", &SessionHandle::grab_end)
      .function("grabbing", &SessionHandle::grabbing)
      .function("brushBegin", &SessionHandle::brush_begin)
      .function("brushStamp", &SessionHandle::brush_stamp)
      .function("brushEnd", &SessionHandle::brush_end)
      .function("brushing", &SessionHandle::brushing)
      .function("mask", &SessionHandle::mask)
      .function("maskBegin", &SessionHandle::mask_begin)
      .function("maskStamp", &SessionHandle::mask_stamp)
      .function("maskEnd", &SessionHandle::mask_end)
      .function("masking", &SessionHandle::masking)
      .function("maskValues", &SessionHandle::mask_values)
      .function("remesh", &SessionHandle::remesh)
      .function("remeshDetail", &SessionHandle::remesh_detail)
      .function("undo", &SessionHandle::undo)
      .function("redo", &SessionHandle::redo)
      .function("canUndo", &SessionHandle::can_undo)
      .function("canRedo", &SessionHandle::can_redo)
      .function("replay", &SessionHandle::replay)
      .function("stats", &SessionHandle::stats)
      .function("quickStats", &SessionHandle::quick_stats)
      .function("exportMesh", &SessionHandle::export_mesh)
      .function("saveState", &SessionHandle::save_state)
      .function("saveChanges", &SessionHandle::save_changes)
      .function("restoreState", &SessionHandle::restore_state)
      .function("restoreSaved", &SessionHandle::restore_state_with)  // (embind 3.1.6: no overload by arity)
      .function("memoryBytes", &SessionHandle::memory_bytes)
      .function("positions", &SessionHandle::positions)
      .function("normals", &SessionHandle::normals)
      .function("indices", &SessionHandle::indices)
      .function("changes", &SessionHandle::changes);
}

}  // namespace adasculpt::bindings
