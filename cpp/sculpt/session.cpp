#include "sculpt/session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "deform/handle_deformer.h"
#include "geometry/aabb_tree.h"
#include "geometry/topology.h"
#include "io/load_mesh.h"
#include "remesh/remesher.h"
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

  std::deque<mesh::SurfaceMesh> undo, redo;  // meshes before / after the steps
  size_t undo_bytes = 0;

  deform::HandleDeformer deformer;
  std::unique_ptr<remesh::Remesher> remesher;  // alive during a grab or a stroke only
  bool grabbing = false;
  BrushStroker brush;
  bool brushing = false;

  mutable geometry::TriangleTree tree;  // of the current surface, built on demand
  mutable bool tree_valid = false;

  FrameTimings last;
  ChangeSet changes;

  void mesh_replaced() {
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
    undo.push_back(mesh);
    undo_bytes += mesh_bytes(undo.back());
    redo.clear();
    while (undo.size() > kMaxUndoSteps || (undo.size() > 1 && undo_bytes > kMaxUndoBytes)) {
      undo_bytes -= mesh_bytes(undo.front());
      undo.pop_front();
    }
  }
  // Ends a grab or a brush stroke, whichever runs.
  void end_grab() {
    if (!grabbing && !brushing) return;
    if (grabbing) deformer.end();
    grabbing = brushing = false;
    remesher.reset();
    if (mesh.has_garbage()) {
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
  const Point picked = tree.closest_point(center).point;
  s.push_undo();
  s.deformer.begin(s.mesh, picked, handle_radius, roi_radius);
  s.remesher = std::make_unique<remesh::Remesher>(s.mesh, s.options);
  s.grabbing = true;
}

void Session::grab_drag(const deform::HandleTransform& total) {
  Impl& s = *impl_;
  if (!s.grabbing) throw std::logic_error("grab_drag: no grab in progress (call grab_begin first)");
  const auto t0 = Clock::now();
  const size_t faces_before = s.mesh.faces_size();
  deform::StepResult& r = s.deformer.step(s.mesh, total, s.options.epsilon);
  const auto t1 = Clock::now();
  const remesh::IterationStats st = s.remesher->iterate_region(r.region);
  FrameTimings& f = s.last;
  f.roi_ms = r.roi_ms;
  f.field_ms = r.field_ms;
  f.refine_ms = r.refine_ms;
  f.deform_ms = r.deform_ms;
  f.remesh_ms = ms_since(t1);
  f.total_ms = ms_since(t0);
  s.tree_valid = false;
  if (st.splits + st.collapses + st.flips > 0 || s.mesh.faces_size() != faces_before) s.changes.topology_changed = true;
  s.changes.touched_vertices.insert(s.changes.touched_vertices.end(), r.region.begin(), r.region.end());
}

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
  // Only the first sample of a stroke needs the tree; it is still valid then unless picking was
  // never done, in which case it is built once for the stroke (as grab_begin does).
  const geometry::TriangleTree* tree = s.brush.started() ? nullptr : &s.surface_tree();
  BrushFrame frame;
  frame.touched.swap(s.changes.touched_vertices);  // appends without copying
  s.brush.sample(s.mesh, *s.remesher, tree, p, pressure, frame);
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
}

void Session::brush_end() { impl_->end_grab(); }
bool Session::brushing() const { return impl_->brushing; }

void Session::brush_stroke(const BrushStroke& stroke) {
  if (stroke.path.empty()) throw std::invalid_argument("brush: 'path' must hold at least one point");
  if (!stroke.pressure.empty() && stroke.pressure.size() != stroke.path.size())
    throw std::invalid_argument("brush: 'pressure' must have one value per path point");
  brush_begin(stroke.settings);
  for (size_t i = 0; i < stroke.path.size(); ++i)
    brush_stamp(stroke.path[i], stroke.pressure.empty() ? 1.0 : stroke.pressure[i]);
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
  remesh::remesh(s.mesh, o);
  if (s.mesh.has_garbage()) s.mesh.garbage_collection();
  s.last = FrameTimings{};
  s.last.remesh_ms = s.last.total_ms = ms_since(t0);
  s.mesh_replaced();
}

bool Session::undo() {
  Impl& s = *impl_;
  s.end_grab();
  if (s.undo.empty()) return false;
  s.redo.push_back(std::move(s.mesh));
  s.mesh = std::move(s.undo.back());
  s.undo_bytes -= mesh_bytes(s.mesh);
  s.undo.pop_back();
  s.mesh_replaced();
  return true;
}

bool Session::redo() {
  Impl& s = *impl_;
  s.end_grab();
  if (s.redo.empty()) return false;
  s.undo.push_back(std::move(s.mesh));
  s.undo_bytes += mesh_bytes(s.undo.back());
  s.mesh = std::move(s.redo.back());
  s.redo.pop_back();
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
  // Brush frames have no field or refinement phase: they stay out of those medians.
  auto record = [&](bool grab_frame) {
    const FrameTimings& f = s.last;
    total.push_back(f.total_ms);
    roi.push_back(f.roi_ms);
    if (grab_frame) {
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

}  // namespace adasculpt::sculpt
