#include "sculpt/session.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <deque>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "geometry/aabb_tree.h"
#include "geometry/topology.h"
#include "io/load_mesh.h"
#include "mesh/build_from_triangles.h"
#include "remesh/remesher.h"
#include "sculpt/grab.h"
#include "sculpt/session_file.h"

namespace adasculpt::sculpt {

namespace {
using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

// Rough heap size of a snapshot, for the history budget.
size_t mesh_bytes(const mesh::SurfaceMesh& m) {
  return m.vertices_size() * (sizeof(Point) + 8) + m.halfedges_size() * 16 + m.edges_size() * 2 +
         m.faces_size() * 8;
}

// save_state() blob, little-endian (native on x86 and wasm; checked below):
//   "ADSCSTAT" u32 version=1, f64 epsilon min_length max_length features diagonal,
//   u32 undo count, u32 redo count, then meshes: current, undo steps oldest..newest, redo steps
//   farthest..nearest (deque order). Mesh: u32 vertices, u32 triangles, f64 xyz..., u32 abc...
constexpr char kStateMagic[8] = {'A', 'D', 'S', 'C', 'S', 'T', 'A', 'T'};
constexpr uint32_t kStateVersion = 1;

size_t serialized_size(const mesh::SurfaceMesh& m) { return 8 + m.n_vertices() * 24 + m.n_faces() * 12; }

template <class T>
void put(std::vector<uint8_t>& out, const T& v) {
  const auto* p = reinterpret_cast<const uint8_t*>(&v);
  out.insert(out.end(), p, p + sizeof(T));
}

// One mesh of the blob: u32 vertices, u32 triangles, f64 xyz..., u32 abc...
std::vector<uint8_t> pack_mesh(const mesh::SurfaceMesh& m) {
  const io::PolygonSoup soup = io::soup_from_mesh(m);
  const uint32_t nv = uint32_t(soup.points.size()), nf = uint32_t(soup.triangles.size());
  std::vector<uint8_t> out(8 + size_t(nv) * 24 + size_t(nf) * 12);
  uint8_t* o = out.data();
  std::memcpy(o, &nv, 4);
  std::memcpy(o + 4, &nf, 4);
  if (nv) std::memcpy(o + 8, soup.points.data(), size_t(nv) * 24);
  o += 8 + size_t(nv) * 24;
  // Rotated so that build_from_triangles (whose face halfedge ends at the second corner) gives
  // back the same face_vertices() order: a save after a restore is byte-identical.
  for (const auto& t : soup.triangles) {
    const uint32_t r[3] = {t[2], t[0], t[1]};
    std::memcpy(o, r, 12);
    o += 12;
  }
  return out;
}

// A packed mesh checked by StateReader::mesh_bytes (counts, finite positions, indices in range).
mesh::SurfaceMesh unpack_mesh(const std::vector<uint8_t>& bytes) {
  uint32_t nv, nf;
  std::memcpy(&nv, bytes.data(), 4);
  std::memcpy(&nf, bytes.data() + 4, 4);
  std::vector<std::array<double, 3>> points(nv);
  std::vector<std::array<uint32_t, 3>> tris(nf);
  if (nv) std::memcpy(points.data(), bytes.data() + 8, size_t(nv) * 24);
  if (nf) std::memcpy(tris.data(), bytes.data() + 8 + size_t(nv) * 24, size_t(nf) * 12);
  try {
    return mesh::build_from_triangles(points, tris);
  } catch (const mesh::TopologyError& e) {
    throw std::invalid_argument(std::string("saved state: ") + e.what());
  }
}

using Packed = std::shared_ptr<const std::vector<uint8_t>>;

struct StateReader {
  const uint8_t* p;
  size_t left;
  [[noreturn]] static void fail(const std::string& what) {
    throw std::invalid_argument("saved state: " + what);
  }
  template <class T>
  T get() {
    if (left < sizeof(T)) fail("truncated");
    T v;
    std::memcpy(&v, p, sizeof(T));
    p += sizeof(T);
    left -= sizeof(T);
    return v;
  }
  // The next packed mesh, checked (everything but the topology, which building checks).
  std::vector<uint8_t> mesh_bytes() {
    const uint8_t* begin = p;
    const uint64_t nv = get<uint32_t>(), nf = get<uint32_t>();
    if (nv * 24 + nf * 12 > left) fail("truncated mesh");
    if (nf == 0) fail("a mesh without faces");
    for (uint64_t i = 0; i < 3 * nv; ++i)
      if (!std::isfinite(get<double>())) fail("non-finite position");
    for (uint64_t i = 0; i < 3 * nf; ++i)
      if (get<uint32_t>() >= nv) fail("vertex index out of range");
    return std::vector<uint8_t>(begin, p);
  }
};

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const double idx = p * double(v.size() - 1);
  const size_t lo = size_t(std::floor(idx)), hi = std::min(v.size() - 1, lo + 1);
  return v[lo] + (idx - double(lo)) * (v[hi] - v[lo]);
}
}  // namespace

struct Session::Impl {
  mesh::SurfaceMesh mesh;
  bool has_mesh = false;
  double diagonal = 0;
  remesh::RemeshOptions options;  // adaptive; epsilon/min/max/features resolved to absolute values

  // One undo or redo step: the mesh, or (restored from a saved state and not needed yet) only its
  // packed bytes, which save_state() also keeps as a cache so that unchanged steps are serialized once.
  struct Snapshot {
    mesh::SurfaceMesh mesh;
    bool built = true;
    mutable Packed packed;
    explicit Snapshot(mesh::SurfaceMesh m) : mesh(std::move(m)) {}
    explicit Snapshot(Packed p) : built(false), packed(std::move(p)) {}
    // For the history budget (the cache of a built mesh is not counted: it comes and goes).
    size_t bytes() const { return built ? mesh_bytes(mesh) : packed->size(); }
    size_t packed_size() const { return packed ? packed->size() : serialized_size(mesh); }
    const std::vector<uint8_t>& pack() const {
      if (!packed) packed = std::make_shared<const std::vector<uint8_t>>(pack_mesh(mesh));
      return *packed;
    }
    mesh::SurfaceMesh take() { return built ? std::move(mesh) : unpack_mesh(*packed); }
  };
  std::deque<Snapshot> undo, redo;  // meshes before / after the steps
  size_t undo_bytes = 0;

  Grab grab;
  std::unique_ptr<remesh::Remesher> remesher;  // alive during a grab or a stroke only
  bool grabbing = false;
  BrushStroker brush;
  bool brushing = false;

  mutable geometry::TriangleTree tree;  // of the current surface, built on demand
  mutable bool tree_valid = false;

  FrameTimings last;
  std::string remesh_warning;  // of the last whole-mesh remesh(); empty when it was within its budget
  ChangeSet changes;

  void mesh_replaced() {
    mesh.reserve_room_for_edits();  // a restored undo step is a copy without room for the next stroke
    tree_valid = false;
    changes.everything = true;
    changes.topology_changed = true;
    changes.touched_vertices.clear();
  }
  const geometry::TriangleTree& surface_tree() const {
    if (!tree_valid) {
      tree.build(mesh);
      tree_valid = true;
    }
    return tree;
  }
  void require_mesh(const char* what) const {
    if (!has_mesh) throw std::logic_error(std::string(what) + ": no mesh loaded");
  }
  void push_undo() {
    undo.emplace_back(mesh);
    undo_bytes += undo.back().bytes();
    redo.clear();
    while (undo.size() > kMaxUndoSteps || (undo.size() > 1 && undo_bytes > kMaxUndoBytes)) {
      undo_bytes -= undo.front().bytes();
      undo.pop_front();
    }
  }
  bool garbage_is_large() const {
    return 8 * (mesh.faces_size() - mesh.n_faces()) > mesh.faces_size() ||
           8 * (mesh.vertices_size() - mesh.n_vertices()) > mesh.vertices_size();
  }
  // Ends a grab or a brush stroke, whichever runs.
  void end_grab() {
    if (!grabbing && !brushing) return;
    if (grabbing) grab.end();
    grabbing = brushing = false;
    remesher.reset();
    // Deleted slots are compacted once they are an eighth of the faces' or vertices' slots, not
    // after every stroke: compaction renumbers the whole mesh (linear in its size, and the viewer
    // uploads every buffer again), which took a seventh of a stroke's time on the 35k-vertex
    // bunny; every reader skips deleted slots (the render buffers draw them as empty triangles).
    if (garbage_is_large()) {
      mesh.garbage_collection();  // renumbers: readers must start over
      mesh_replaced();
    }
    tree_valid = false;
  }
};

Session::Session() : impl_(std::make_unique<Impl>()) {}
Session::~Session() = default;

void Session::load(mesh::SurfaceMesh m) {
  if (m.n_faces() == 0) throw std::invalid_argument("the mesh has no faces");
  Impl& s = *impl_;
  s.end_grab();
  if (m.has_garbage()) m.garbage_collection();
  s.mesh = std::move(m);
  s.has_mesh = true;
  s.undo.clear();
  s.redo.clear();
  s.undo_bytes = 0;
  s.options = remesh::default_options_for(s.mesh);
  s.options.adaptive = true;
  s.options.feature_angle_deg = 0;
  s.diagonal = geometry::bounding_box_diagonal(s.mesh);
  s.last = FrameTimings{};
  s.mesh_replaced();
}

void Session::load_bytes(const uint8_t* data, size_t size, const std::string& name_hint) {
  load(io::load_mesh_from_memory(data, size, name_hint));
}

void Session::load_file(const std::string& path) { load(io::load_mesh(path)); }

bool Session::has_mesh() const { return impl_->has_mesh; }
const mesh::SurfaceMesh& Session::mesh() const { return impl_->mesh; }

void Session::set_settings(const nlohmann::json& j) {
  Impl& s = *impl_;
  const SettingsPatch p = parse_settings(j, "settings: ");
  remesh::RemeshOptions o = s.options;
  if (p.epsilon) o.epsilon = p.epsilon->resolve(s.diagonal);
  if (p.min_length) o.min_length = p.min_length->resolve(s.diagonal);
  if (p.max_length) o.max_length = p.max_length->resolve(s.diagonal);
  if (p.features) o.feature_angle_deg = *p.features;
  if (o.min_length > o.max_length)
    throw std::invalid_argument("settings: 'min_length' must not exceed 'max_length'");
  remesh::check_options(o);
  s.options = o;
  if (s.remesher) s.remesher->set_options(o);
}

nlohmann::json Session::settings() const {
  const Impl& s = *impl_;
  return {{"epsilon", s.options.epsilon},
          {"min_length", s.options.min_length},
          {"max_length", s.options.max_length},
          {"features", s.options.feature_angle_deg},
          {"diagonal", s.diagonal}};
}

bool Session::pick(const Point& origin, const Vec3& dir, Point* hit) const {
  if (!impl_->has_mesh || !(glm::length(dir) > 0)) return false;
  const geometry::TriangleTree& tree = impl_->surface_tree();
  if (tree.empty()) return false;
  const auto h = tree.intersect_ray(origin, dir);
  if (h.hit && hit) *hit = h.point;
  return h.hit;
}

void Session::grab_begin(const Point& center, double handle_radius, double roi_radius) {
  Impl& s = *impl_;
  s.require_mesh("grab");
  if (!(handle_radius >= 0) || !std::isfinite(handle_radius))
    throw std::invalid_argument("grab: 'handle_radius' must be a non-negative number");
  if (!(roi_radius > 0) || !std::isfinite(roi_radius))
    throw std::invalid_argument("grab: 'roi_radius' must be a positive number");
  s.end_grab();
  const geometry::TriangleTree& tree = s.surface_tree();
  if (tree.empty()) throw std::invalid_argument("grab: the mesh has no non-degenerate face");
  const geometry::TriangleTree::ClosestHit hit = tree.closest_point(center);
  s.push_undo();
  s.grab.begin(s.mesh, hit.point, tree.face_of(hit.triangle), handle_radius, roi_radius);
  s.remesher = std::make_unique<remesh::Remesher>(s.mesh, s.options);
  s.grabbing = true;
}

void Session::grab_drag(const deform::HandleTransform& total) {
  Impl& s = *impl_;
  if (!s.grabbing) throw std::logic_error("grab_drag: no grab in progress (call grab_begin first)");
  s.grab.drag(s.mesh, *s.remesher, total, s.options.epsilon, s.last, s.changes);
  s.tree_valid = false;
}

deform::DeformOptions& Session::grab_options() { return impl_->grab.options(); }

void Session::grab_end() { impl_->end_grab(); }
bool Session::grabbing() const { return impl_->grabbing; }

void Session::brush_begin(const deform::BrushSettings& settings) {
  Impl& s = *impl_;
  s.require_mesh("brush");
  deform::check_brush_settings(settings);
  s.end_grab();
  s.brush.begin(settings);
  s.push_undo();
  s.remesher = std::make_unique<remesh::Remesher>(s.mesh, s.options);
  s.brushing = true;
}

void Session::brush_stamp(const Point& p, double pressure) {
  Impl& s = *impl_;
  if (!s.brushing) throw std::logic_error("brush_stamp: no stroke in progress (call brush_begin first)");
  const auto t0 = Clock::now();
  BrushFrame frame;
  frame.touched.swap(s.changes.touched_vertices);  // appends without copying
  s.brush.sample(s.mesh, *s.remesher, p, pressure, frame);
  frame.touched.swap(s.changes.touched_vertices);
  if (frame.topology_changed) s.changes.topology_changed = true;
  if (frame.stamps > 0) s.tree_valid = false;
  FrameTimings& f = s.last;
  f = FrameTimings{};
  f.roi_ms = frame.locate_ms;
  f.deform_ms = frame.deform_ms;
  f.remesh_ms = frame.remesh_ms;
  f.total_ms = ms_since(t0);
  f.stamps = frame.stamps;
  if (frame.limit_reached) {  // reported once; the stroke's later samples are ignored
    throw std::runtime_error("brush: stroke stopped at " + std::to_string(s.mesh.n_faces()) + " faces, past the " +
                             std::to_string(s.brush.face_budget()) +
                             " one stroke may grow this mesh to; undo it, or raise epsilon or the minimum edge "
                             "length for less detail");
  }
}

void Session::brush_end() { impl_->end_grab(); }
bool Session::brushing() const { return impl_->brushing; }

void Session::brush_stroke(const BrushStroke& stroke) {
  if (stroke.path.empty()) throw std::invalid_argument("brush: 'path' must hold at least one point");
  if (!stroke.pressure.empty() && stroke.pressure.size() != stroke.path.size())
    throw std::invalid_argument("brush: 'pressure' must have one value per path point");
  brush_begin(stroke.settings);
  try {
    for (size_t i = 0; i < stroke.path.size(); ++i)
      brush_stamp(stroke.path[i], stroke.pressure.empty() ? 1.0 : stroke.pressure[i]);
  } catch (...) {
    brush_end();  // what was stamped stays, as one undo step
    throw;
  }
  brush_end();
}

void Session::remesh(int iterations) {
  Impl& s = *impl_;
  s.require_mesh("remesh");
  if (iterations < 1) throw std::invalid_argument("remesh: 'iterations' must be a positive integer");
  s.end_grab();
  const auto t0 = Clock::now();
  s.push_undo();
  remesh::RemeshOptions o = s.options;
  o.projection = true;
  o.iterations = iterations;
  s.remesh_warning = remesh::remesh(s.mesh, o).warning;
  if (s.mesh.has_garbage()) s.mesh.garbage_collection();
  s.last = FrameTimings{};
  s.last.remesh_ms = s.last.total_ms = ms_since(t0);
  s.mesh_replaced();
}

bool Session::undo() {
  Impl& s = *impl_;
  s.end_grab();
  if (s.undo.empty()) return false;
  const size_t bytes = s.undo.back().bytes();
  mesh::SurfaceMesh m = s.undo.back().take();  // builds a restored step; throws before any change
  s.undo_bytes -= bytes;
  s.undo.pop_back();
  s.redo.emplace_back(std::move(s.mesh));
  s.mesh = std::move(m);
  s.mesh.garbage_collection();  // a stroke may have left deleted slots; the buffers start over anyway
  s.mesh_replaced();
  return true;
}

bool Session::redo() {
  Impl& s = *impl_;
  s.end_grab();
  if (s.redo.empty()) return false;
  mesh::SurfaceMesh m = s.redo.back().take();
  s.redo.pop_back();
  s.undo.emplace_back(std::move(s.mesh));
  s.undo_bytes += s.undo.back().bytes();
  s.mesh = std::move(m);
  s.mesh.garbage_collection();  // as in undo()
  s.mesh_replaced();
  return true;
}

bool Session::can_undo() const { return !impl_->undo.empty() || impl_->grabbing || impl_->brushing; }
bool Session::can_redo() const { return !impl_->redo.empty() && !impl_->grabbing && !impl_->brushing; }

nlohmann::json Session::replay(const nlohmann::json& session_file) {
  Impl& s = *impl_;
  const SessionFile file = parse_session_file(session_file);  // all errors before any change
  s.require_mesh("replay");
  set_settings(to_json(file.settings));
  std::vector<double> total, roi, field, refine, deform, rem;
  bool roi_capped = false;
  // Brush frames have no field or refinement phase: they stay out of those medians.
  auto record = [&](bool grab_frame) {
    const FrameTimings& f = s.last;
    total.push_back(f.total_ms);
    roi.push_back(f.roi_ms);
    if (grab_frame) {
      roi_capped = roi_capped || f.roi_capped;
      field.push_back(f.field_ms);
      refine.push_back(f.refine_ms);
    }
    deform.push_back(f.deform_ms);
    rem.push_back(f.remesh_ms);
  };
  for (const SessionStep& step : file.steps) {
    switch (step.kind) {
      case SessionStep::Kind::Grab: {
        const GrabStep& g = step.grab;
        grab_begin(g.center, g.handle_radius, g.roi_radius);
        for (int i = 1; i <= g.substeps; ++i) {
          grab_drag(g.total_at(double(i) / g.substeps));
          record(true);
        }
        grab_end();
        break;
      }
      case SessionStep::Kind::Brush: {
        const BrushStroke& b = step.brush;
        brush_begin(b.settings);
        for (size_t i = 0; i < b.path.size(); ++i) {
          brush_stamp(b.path[i], b.pressure.empty() ? 1.0 : b.pressure[i]);
          record(false);
        }
        brush_end();
        break;
      }
      case SessionStep::Kind::Remesh:
        remesh(step.count);
        break;
      case SessionStep::Kind::Undo:
        for (int i = 0; i < step.count; ++i) undo();
        break;
      case SessionStep::Kind::Redo:
        for (int i = 0; i < step.count; ++i) redo();
        break;
    }
  }
  const geometry::QualityReport q = quality();
  return {{"frames", total.size()},
          {"frame_ms_median", percentile(total, 0.5)},
          {"frame_ms_p95", percentile(total, 0.95)},
          {"frame_ms_max", total.empty() ? 0.0 : *std::max_element(total.begin(), total.end())},
          {"roi_ms_median", percentile(roi, 0.5)},
          {"field_ms_median", percentile(field, 0.5)},
          {"refine_ms_median", percentile(refine, 0.5)},
          {"deform_ms_median", percentile(deform, 0.5)},
          {"remesh_ms_median", percentile(rem, 0.5)},
          {"roi_capped", roi_capped},
          {"vertices", q.vertices},
          {"faces", q.faces},
          {"min_angle_deg", q.min_angle_deg},
          {"mean_min_angle_deg", q.mean_min_angle_deg}};
}

geometry::QualityReport Session::quality() const {
  impl_->require_mesh("quality");
  return geometry::quality_report(impl_->mesh);
}
const FrameTimings& Session::last_frame() const { return impl_->last; }

const std::string& Session::remesh_warning() const { return impl_->remesh_warning; }
const ChangeSet& Session::changes() const { return impl_->changes; }
void Session::clear_changes() {
  impl_->changes.topology_changed = false;
  impl_->changes.everything = false;
  impl_->changes.touched_vertices.clear();
}

std::vector<uint8_t> Session::export_bytes(io::Format f) const {
  impl_->require_mesh("export");
  return io::save_mesh_to_memory(impl_->mesh, f);
}

std::vector<uint8_t> Session::save_state(size_t max_history_bytes) const {
  const Impl& s = *impl_;
  s.require_mesh("save state");
  if (s.grabbing || s.brushing) throw std::logic_error("save state: a grab or a stroke is in progress");
  static_assert(sizeof(std::array<double, 3>) == 24 && sizeof(std::array<uint32_t, 3>) == 12, "packed arrays");
  const uint32_t probe = 1;
  if (*reinterpret_cast<const uint8_t*>(&probe) != 1) throw std::logic_error("save state: big-endian host");
  // Newest undo steps first, then the nearest redo steps, while they fit the budget.
  size_t used = 0, n_undo = 0, n_redo = 0;
  for (auto it = s.undo.rbegin(); it != s.undo.rend(); ++it, ++n_undo) {
    const size_t b = it->packed_size();
    if (used + b > max_history_bytes) break;
    used += b;
  }
  if (n_undo == s.undo.size())
    for (auto it = s.redo.rbegin(); it != s.redo.rend(); ++it, ++n_redo) {
      const size_t b = it->packed_size();
      if (used + b > max_history_bytes) break;
      used += b;
    }
  const std::vector<uint8_t> current = pack_mesh(s.mesh);
  std::vector<uint8_t> out;
  out.reserve(64 + current.size() + used);
  for (char c : kStateMagic) out.push_back(uint8_t(c));  // (vector::insert of the char range trips a g++ 12 false -Wstringop-overflow)
  put(out, kStateVersion);
  for (double x : {s.options.epsilon, s.options.min_length, s.options.max_length, s.options.feature_angle_deg,
                   s.diagonal})
    put(out, x);
  put(out, uint32_t(n_undo));
  put(out, uint32_t(n_redo));
  out.insert(out.end(), current.begin(), current.end());
  auto append = [&](const Impl::Snapshot& snap) {
    const std::vector<uint8_t>& b = snap.pack();  // serialized once per step, then cached
    out.insert(out.end(), b.begin(), b.end());
  };
  for (size_t i = s.undo.size() - n_undo; i < s.undo.size(); ++i) append(s.undo[i]);
  for (size_t i = s.redo.size() - n_redo; i < s.redo.size(); ++i) append(s.redo[i]);
  return out;
}

void Session::restore_state(const uint8_t* data, size_t size) {
  StateReader r{data, size};
  if (size < 8 || std::memcmp(data, kStateMagic, 8) != 0) r.fail("not an adasculpt state (bad magic)");
  r.p += 8;
  r.left -= 8;
  const uint32_t version = r.get<uint32_t>();
  if (version != kStateVersion) r.fail("unsupported version " + std::to_string(version));
  double v[5];
  for (double& x : v) x = r.get<double>();
  const uint32_t n_undo = r.get<uint32_t>(), n_redo = r.get<uint32_t>();
  if (uint64_t(n_undo) + n_redo > (r.left + 1) / 8) r.fail("truncated history");
  mesh::SurfaceMesh current = unpack_mesh(r.mesh_bytes());
  // The steps stay packed until undo/redo needs them (a restore costs one mesh build, not one per step).
  std::deque<Impl::Snapshot> undo, redo;
  for (uint32_t i = 0; i < n_undo; ++i) undo.emplace_back(std::make_shared<const std::vector<uint8_t>>(r.mesh_bytes()));
  while (undo.size() > kMaxUndoSteps) undo.pop_front();
  for (uint32_t i = 0; i < n_redo; ++i) redo.emplace_back(std::make_shared<const std::vector<uint8_t>>(r.mesh_bytes()));
  if (r.left != 0) r.fail(std::to_string(r.left) + " unexpected bytes at the end");
  remesh::RemeshOptions o = remesh::default_options_for(current);
  o.adaptive = true;
  o.epsilon = v[0];
  o.min_length = v[1];
  o.max_length = v[2];
  o.feature_angle_deg = v[3];
  if (!(v[4] > 0) || !std::isfinite(v[4])) r.fail("bad diagonal");
  if (!(o.min_length <= o.max_length)) r.fail("'min_length' exceeds 'max_length'");
  try {
    remesh::check_options(o);
  } catch (const std::exception& e) {
    r.fail(e.what());
  }
  // Everything parsed: commit (moves only).
  Impl& s = *impl_;
  s.end_grab();
  s.mesh = std::move(current);
  s.has_mesh = true;
  s.undo = std::move(undo);
  s.redo = std::move(redo);
  s.undo_bytes = 0;
  for (const auto& m : s.undo) s.undo_bytes += m.bytes();
  s.options = o;
  s.diagonal = v[4];
  s.last = FrameTimings{};
  s.mesh_replaced();
}

size_t Session::undo_steps() const { return impl_->undo.size(); }
size_t Session::redo_steps() const { return impl_->redo.size(); }
size_t Session::memory_bytes() const {
  const Impl& s = *impl_;
  size_t b = s.has_mesh ? mesh_bytes(s.mesh) : 0;
  b += s.undo_bytes;
  for (const auto& m : s.redo) b += m.bytes();
  return b;
}

}  // namespace adasculpt::sculpt
