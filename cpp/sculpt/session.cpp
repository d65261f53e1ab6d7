#include "sculpt/session.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <deque>
#include <memory>
#include <random>
#include <stdexcept>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "geometry/angle_figures.h"
#include "geometry/face_slot_tree.h"
#include "geometry/mirror_tracker.h"
#include "geometry/topology.h"
#include "io/load_mesh.h"
#include "mesh/clock.h"
#include "mesh/flat_walk.h"
#include "mesh/build_from_triangles.h"
#include "mesh/vertex_mask.h"
#include "remesh/remesher.h"
#include "sculpt/component_box.h"
#include "sculpt/grab.h"
#include "sculpt/session_file.h"
#include "sculpt/session_state.h"
#include "sculpt/state_changes.h"
#include "sculpt/undo_log.h"

namespace adasculpt::sculpt {

namespace {

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
  std::vector<std::string> load_warnings;  // (Session::load_warnings)
  double diagonal = 0;
  remesh::RemeshOptions options;  // adaptive; epsilon/min/max/features resolved to absolute values
  bool guard_crossings = false;   // set_settings; kept through loads (a preference, not a length)

  // The history as a log of slot changes (undo_log.h). The mesh is never compacted while it holds
  // steps (they refer to slots); step_touched gathers the current step's touched vertices across
  // clear_changes() calls.
  UndoLog history;
  // The changes since the last saved state, for incremental autosave (state_changes.h); started
  // by save_state and restore_state, stopped by anything that is not a local step.
  ChangeJournal journal;
  std::vector<mesh::Vertex> step_touched;
  size_t step_touched_from = 0;  // where the current step's vertices start in changes.touched_vertices
  // step_touched holds each vertex once: a grab touches its whole region every frame, and the
  // list grew by the region each frame (600k entries for a 60-frame pull of a 10k ROI).
  std::vector<std::uint32_t> step_mark;  // per vertex slot: step_epoch when in step_touched
  std::uint32_t step_epoch = 0;

  Grab grab;
  // Made with the mesh and kept through strokes, grabs, undo and redo: making one marks the
  // feature or boundary edges and classifies every vertex, a pass over the whole mesh (2.5 ms a
  // stroke at 1.1M triangles, 5.8 ms for the first stroke after each undo). Its per-slot arrays
  // follow the strokes' splits and collapses, and Remesher::reset_slots brings the slots a stroke,
  // a grab, an undo or a redo changed back to a new remesher's state. A new mesh (load, restore,
  // whole remesh, a whole-mesh undo step) gets a new one.
  std::unique_ptr<remesh::Remesher> remesher;
  bool remesher_kept = false;  // in a new remesher's state, between strokes and grabs

  // Detail that follows the object: a stroke applies the detail settings (fractions of the scene's
  // diagonal) to the connected component under the brush, so loading more objects does not make
  // every stroke coarser. The component's diagonal is measured at the stroke's start (a walk over
  // it, or read from component_box when it follows that component), and reused while strokes start
  // on the same component.
  double component_diagonal = 0;  // of the last stroke's component; 0 = unknown
  // Which of epsilon, min_length, max_length are fractions of the diagonal (the defaults, and
  // percentages): those follow the object; lengths given as numbers stay as given.
  bool relative[3] = {true, true, true};
  // The component's box, followed through strokes, grabs, undo and redo: a stroke after an undo
  // reads the diagonal a walk would give from it (component_box.h).
  ComponentBox component_box;
  bool grabbing = false;
  BrushStroker brush;
  bool brushing = false;
  MaskPainter mask_painter;
  bool masking = false;  // a mask stroke runs (mask_begin .. mask_end)

  // A mask operation starts: ends whatever runs, gives the mesh its mask on first use, opens the
  // step (recorded by commit_step, or by end_grab for a stroke).
  void start_mask_step() {
    require_mesh("mask");
    end_grab();
    if (!mesh::find_mask(mesh).is_valid()) {
      mesh.add_vertex_property<float>(mesh::kMaskProperty, 0.0f);
      history.adopt_new_arrays(mesh);  // all zero on both sides: the step logs the change
      journal.stop();  // a change record cannot add an array: the next save is a full state
    }
    push_undo();
    last = FrameTimings{};
  }

  // Picking, a grab's press, a stroke's start and the mask brush find the surface through boxes
  // over the face slots that follow the changes (face_slot_tree.h): built with each new mesh, then
  // refitted where strokes, grabs, undo and redo changed it. The changes reach it from `changes`
  // (noted_* say how much of its lists it has seen), so clear_changes() notes them first.
  mutable geometry::FaceSlotTree slot_tree;
  // find_mirror_map's answer kept through every change at the change's cost (mirror_tracker.h):
  // a symmetric stroke borrows the map (no search over the mesh after an undo, a redo, a grab or
  // a one-sided stroke), and a mesh that is not symmetric keeps a witness instead of being read
  // whole at every symmetric stroke. mirror_lent: the running stroke's remesher holds its map.
  geometry::MirrorTracker mirror;
  bool mirror_lent = false;
  bool mirror_map_whole = false;  // the stroke that ended handed the whole map back
  bool mirror_tracking = true;  // off (tests): every symmetric stroke searches, as a new session does
  // The plane a new mesh's map is prepared for at its load: the app's default symmetry (across x),
  // then the last symmetric stroke's.
  int mirror_axis_hint = 0;
  // The stats shown after every stroke (quick_quality), kept from the same changes.
  mutable geometry::AngleFigures angle_figures;
  mutable size_t noted_vertices = 0, noted_faces = 0;

  FrameTimings last;
  std::string remesh_warning;  // of the last whole-mesh remesh(); empty when it was within its budget
  ChangeSet changes;

  // A grab's or a stroke's remesher; its collapses report the face slots they delete, which no
  // vertex reaches any more, to the render buffers through changes.touched_faces.
  void make_remesher() {
    remesher.reset();  // first: a remesher takes its arrays off the mesh when it goes
    remesher = std::make_unique<remesh::Remesher>(mesh, options);
    remesher->set_region_crossing_guard(guard_crossings);  // before its scratch is reserved
    remesher->log_deleted_faces(&changes.touched_faces);
  }
  void drop_remesher() {
    remesher.reset();
    remesher_kept = false;
  }
  // A stroke found the surface at `seed`: its remeshing options, the detail settings scaled from
  // the scene's diagonal to the component's (or the stroke's own constant detail).
  void start_stroke(mesh::Vertex seed, bool same_component) {
    if (!same_component || !(component_diagonal > 0)) {
      component_diagonal = component_box.known_diagonal(mesh, seed);
      if (!(component_diagonal > 0)) component_diagonal = component_box.measure(mesh, seed);
    }
    remesh::RemeshOptions o = options;
    const double scale = component_diagonal > 0 && diagonal > 0 ? component_diagonal / diagonal : 1.0;
    if (relative[0]) o.epsilon *= scale;
    if (relative[1]) o.min_length *= scale;
    if (relative[2]) o.max_length *= scale;
    if (o.min_length > o.max_length) o.min_length = o.max_length;  // one relative, the other not
    set_constant_detail(o, brush.settings().detail);
    remesher->set_options(o);
  }
  // Constant detail (> 0): the clamp gives every edge this length (Remesher: clamp_decides_sizing).
  static void set_constant_detail(remesh::RemeshOptions& o, double detail) {
    if (!(detail > 0)) return;
    o.min_length = o.max_length = detail;
    o.epsilon = std::min(o.epsilon, detail);
  }
  void mesh_replaced() {
    component_diagonal = 0;
    drop_remesher();
    if (options.epsilon > 0) {
      // The strokes' remesher, made with the mesh (its arrays on a 1.1M-triangle mesh are a
      // per-mesh cost: made in the first stroke they took a few hundred milliseconds of it).
      make_remesher();
      remesher_kept = true;
    }
    mesh.reserve_room_for_edits();  // a restored undo step is a copy without room for the next stroke
    // The per-slot scratch of strokes, sized (and zero-filled) with the mesh: sized in a stroke,
    // they made each session's first stroke on 1.1M triangles cost ~15 ms more than on 70k, and
    // the process's first ~55 ms more (allocation and first-touch page faults; issue 18).
    if (remesher) remesher->reserve_scratch();
    brush.deformer().grow(mesh.vertices_size());
    const size_t marks = mesh.vertices_size() * 5 / 4 + 16;  // as move_step_touched
    component_box.reset(mesh.vertices_size());
    // The object holding the first vertex (a one-object scan: the mesh) measured here, with the
    // mesh, rather than walked by the first stroke on it.
    if (mesh.n_vertices() > 0) component_box.measure(mesh, *mesh.vertices().begin());
    if (step_mark.size() < marks) step_mark.resize(marks, 0u);
    // Built here, with the mesh (a sort and a pass over its faces: ~0.3 s at 1.1M triangles), not
    // at the first stroke or press after the load, where it would be a hitch.
    slot_tree.invalidate();
    slot_tree.sync(mesh);
    // The map the first symmetric stroke takes, prepared here (the load reads every vertex anyway):
    // a search in that stroke was a 63-68 ms hitch at 1.1M triangles.
    mirror.prepare(mesh, mirror_axis_hint);
    mirror_lent = false;
    lend_mirror_map_once();
    angle_figures.invalidate();
    changes.everything = true;
    changes.topology_changed = true;
    changes.touched_vertices.clear();
    changes.touched_faces.clear();
    noted_vertices = noted_faces = 0;
  }
  // Hands the changes made since the last call to the slot tree and the angle figures (they mark
  // what to refit or recompute at their next sync).
  void note_changes() const {
    const auto& tv = changes.touched_vertices;
    const auto& tf = changes.touched_faces;
    for (size_t i = std::min(noted_vertices, tv.size()); i < tv.size(); ++i) {
      slot_tree.mark_vertex(mesh, tv[i]);
      angle_figures.mark_vertex(mesh, tv[i]);
    }
    for (size_t i = std::min(noted_faces, tf.size()); i < tf.size(); ++i) {
      slot_tree.mark_face(tf[i]);
      angle_figures.mark_face(tf[i]);
    }
    noted_vertices = tv.size();
    noted_faces = tf.size();
  }
  const geometry::FaceSlotTree& surface() const {
    note_changes();
    slot_tree.sync(mesh);
    return slot_tree;
  }
  // The surface point nearest q (exact) and its face; throws without a face.
  geometry::FaceSlotTree::Hit closest_on_surface(const Point& q, const char* what) const {
    const geometry::FaceSlotTree::Hit hit = surface().closest_point(mesh, q);
    if (!hit.face.is_valid()) throw std::invalid_argument(std::string(what) + ": the mesh has no face");
    return hit;
  }
  // A grab's press or a stroke's start: the surface point nearest `center` and the vertex nearest
  // that point (as sculpt::locate_on_surface, which scanned every vertex).
  mesh::Vertex locate_press(const Point& center, Point* picked, const char* what = "grab") const {
    const geometry::FaceSlotTree::Hit hit = closest_on_surface(center, what);
    mesh::Vertex corners[3];
    mesh.face_vertices(hit.face, corners);
    const int k = int(std::max_element(hit.bary, hit.bary + 3) - hit.bary);
    *picked = hit.point;
    return deform::walk_to_nearest_vertex(mesh, corners[k], hit.point);
  }
  StateSettings state_settings() const {
    return {options.epsilon, options.min_length, options.max_length, options.feature_angle_deg, diagonal};
  }
  void require_mesh(const char* what) const {
    if (!has_mesh) throw std::logic_error(std::string(what) + ": no mesh loaded");
  }
  // A grab or a stroke starts: its step is recorded when it ends (commit_step).
  void push_undo() {
    step_touched.clear();
    step_touched_from = changes.touched_vertices.size();
    if (++step_epoch == 0) {
      std::fill(step_mark.begin(), step_mark.end(), 0u);
      step_epoch = 1;
    }
  }
  // The step's share of changes.touched_vertices (the viewer may not have read earlier ones yet).
  void move_step_touched() {
    const auto& t = changes.touched_vertices;
    if (step_mark.size() < mesh.vertices_size()) step_mark.resize(mesh.vertices_size() * 5 / 4 + 16, 0u);
    for (size_t i = std::min(step_touched_from, t.size()); i < t.size(); ++i) {
      const mesh::Vertex v = t[i];
      if (v.idx >= step_mark.size()) step_mark.resize(size_t(v.idx) * 5 / 4 + 16, 0u);
      if (step_mark[v.idx] == step_epoch) continue;
      step_mark[v.idx] = step_epoch;
      step_touched.push_back(v);
    }
    step_touched_from = t.size();  // clear_changes() starts it over
  }
  void commit_step() {
    move_step_touched();
    history.commit_local(mesh, step_touched);
    follow_mirror(mirror_map_whole);
    mirror_map_whole = false;
    journal.commit(history, mesh);
    step_touched.clear();
    step_touched.shrink_to_fit();
  }
  // After load, restore or a whole remesh: the mesh has no deleted slots and the history starts over
  // (or holds whole-mesh steps only at this point).
  void new_base() {
    history.reset(mesh);
    history.set_limits(kMaxUndoSteps, kMaxUndoBytes);
  }
  // The mirror map follows the slots the last step, undo or redo changed (the history knows them
  // all, deleted ones included); map_whole: a stroke handed back the whole map.
  void follow_mirror(bool map_whole) {
    const std::vector<mesh::Vertex>* changed = history.last_changed_vertices();
    if (!changed)
      mirror.forget();
    else if (map_whole)
      mirror.follow_with_map(mesh, *changed);
    else
      mirror.follow(mesh, *changed);
  }
  // The remesher borrows the map once outside a stroke (a new mesh, new feature settings), so that
  // the first symmetric stroke finds it ready: the mesh's mirror array made from it takes room for
  // the mesh's growth (a copy of the map, 3.3M instructions at 1.1M triangles, kept by later
  // strokes), and with features on the remesher finds the feature edges whose image is no feature
  // here, and then only around what changed (else the first stroke would read every edge).
  // Borrowing the map and giving it back changes nothing else. False: no map to lend.
  bool lend_mirror_map_once() {
    if (!remesher || !mirror_tracking) return false;
    std::vector<mesh::Vertex>* map = mirror.map(mesh, mirror_axis_hint);
    if (!map || !mirror.mask_symmetric()) return false;
    remesher->enable_mirror(mirror_axis_hint, *map);
    remesher->disable_mirror(mirror.lent_storage());
    return true;
  }
  // A symmetric stroke starts: the remesher borrows the kept map (or searches, with tracking off).
  bool start_mirror(const mesh::SurfaceMesh& m, remesh::Remesher& r, int axis) {
    mirror_axis_hint = axis;
    if (!mirror_tracking) return r.enable_mirror(axis);
    std::vector<mesh::Vertex>* map = mirror.map(m, axis);
    mirror_lent = map && mirror.mask_symmetric() && r.enable_mirror(axis, *map);
    return mirror_lent;
  }
  // Ends a grab or a brush stroke, whichever runs.
  void end_grab() {
    if (!grabbing && !brushing && !masking) return;
    if (grabbing) grab.end(mesh, *remesher, changes);
    if (brushing || grabbing) {
      // A stroke that mirrored to its end changed the mesh only through its mirrored stamps and
      // passes: the map it borrowed comes back as the mesh's map. Anything else is followed from
      // the slots it touched.
      mirror_map_whole = remesher->disable_mirror(mirror_lent ? mirror.lent_storage() : nullptr);
      // A map that came back not matching the mesh (the stroke lost the symmetry on the way) still
      // holds the right entries for the slots the stroke did not touch (only its own operations
      // rewrote entries): it is followed from the touched slots like any change. One that did not
      // come back is forgotten (the next question settles every vertex).
      if (mirror_lent && !mirror_map_whole && mirror.lent_storage()->empty()) mirror.forget_map();
      mirror_lent = false;
      // The sizing the stroke or grab measured goes back to unmeasured and the marks around what
      // it moved follow the new surface: the next one starts as with a new remesher.
      move_step_touched();
      remesher->reset_slots(step_touched);
      remesher->note_mirror_changes(step_touched);
      remesher_kept = true;
      component_box.follow(mesh, step_touched);
    }  // (a mask stroke changes no geometry: a kept remesher and the surface tree stay valid)
    grabbing = brushing = masking = false;
    // The step is recorded from the slots around what it touched (no pass over the mesh). The
    // mesh is not compacted here: the history refers to slots, and deleted slots stay until a
    // whole-mesh step (load, restore, remesh) starts the numbering over. Every reader skips them
    // (the render buffers draw them as empty triangles).
    commit_step();
  }
  bool step_history(bool back) {
    end_grab();
    std::vector<mesh::Vertex> touched;
    bool whole = false;
    const bool done = back ? history.undo(mesh, &touched, &whole, &changes.touched_faces)
                           : history.redo(mesh, &touched, &whole, &changes.touched_faces);
    if (!done) return false;
    if (back)
      journal.undo();
    else
      journal.redo();
    if (whole) {
      mesh_replaced();
    } else {
      // The remesher's arrays are not in the history: the slots the step swapped back hold what
      // they held before it. reset_slots gives them (and the marks around them) a new remesher's
      // values, without its pass over the mesh.
      if (remesher) {
        remesher->reset_slots(touched);
        remesher->note_mirror_changes(touched);
      }
      follow_mirror(false);
      component_box.follow(mesh, touched);
      component_diagonal = 0;  // the next stroke takes the diagonal the mesh has now (component_box)
      changes.topology_changed = true;
      changes.touched_vertices.insert(changes.touched_vertices.end(), touched.begin(), touched.end());
    }
    return true;
  }
};

Session::Session() : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.brush.set_start_hook([&s](const mesh::SurfaceMesh&, mesh::Vertex seed, bool walked) { s.start_stroke(seed, walked); });
  s.brush.set_locator([&s](const mesh::SurfaceMesh&, const Point& p, Point* on_surface) {
    return s.locate_press(p, on_surface, "brush");
  });
  s.brush.set_mirror_start([&s](const mesh::SurfaceMesh& m, remesh::Remesher& r, int axis) { return s.start_mirror(m, r, axis); });
}
Session::~Session() = default;

void Session::load(mesh::SurfaceMesh m, std::vector<std::string> warnings) {
  if (m.n_faces() == 0) throw std::invalid_argument("the mesh has no faces");
  Impl& s = *impl_;
  s.load_warnings = std::move(warnings);
  s.end_grab();
  if (m.has_garbage()) m.garbage_collection();
  s.drop_remesher();  // before the mesh it holds arrays on goes
  s.mesh = std::move(m);
  s.has_mesh = true;
  s.new_base();
  s.journal.stop();
  for (bool& r : s.relative) r = true;
  s.options = remesh::default_options_for(s.mesh);
  s.options.adaptive = true;
  s.options.feature_angle_deg = 0;
  s.diagonal = geometry::bounding_box_diagonal(s.mesh);
  s.last = FrameTimings{};
  s.mesh_replaced();
}

void Session::load_bytes(const uint8_t* data, size_t size, const std::string& name_hint) {
  std::vector<std::string> warnings;
  mesh::SurfaceMesh m = io::load_mesh_from_memory(data, size, name_hint, &warnings);
  load(std::move(m), std::move(warnings));
}

void Session::load_file(const std::string& path) {
  std::vector<std::string> warnings;
  mesh::SurfaceMesh m = io::load_mesh(path, &warnings);
  load(std::move(m), std::move(warnings));
}

const std::vector<std::string>& Session::load_warnings() const { return impl_->load_warnings; }

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
  const std::optional<LengthSetting>* given[3] = {&p.epsilon, &p.min_length, &p.max_length};
  for (int i = 0; i < 3; ++i)
    if (*given[i]) s.relative[i] = (*given[i])->percent;
  if (s.remesher) s.remesher->set_options(o);
  if (p.guard_crossings && *p.guard_crossings != s.guard_crossings) {
    s.guard_crossings = *p.guard_crossings;
    if (s.remesher) {
      s.remesher->set_region_crossing_guard(s.guard_crossings);
      // The guard's per-slot arrays, here rather than in the next stroke (none when it goes off).
      if (s.guard_crossings) s.remesher->reserve_scratch();
    }
  }
  if (p.features && s.options.feature_angle_deg > 0 && s.has_mesh && !s.grabbing && !s.brushing && !s.masking)
    s.lend_mirror_map_once();
}

nlohmann::json Session::settings() const {
  const Impl& s = *impl_;
  return {{"epsilon", s.options.epsilon},
          {"min_length", s.options.min_length},
          {"max_length", s.options.max_length},
          {"features", s.options.feature_angle_deg},
          {"guard_crossings", s.guard_crossings},
          {"diagonal", s.diagonal}};
}

bool Session::pick(const Point& origin, const Vec3& dir, Point* hit) const {
  if (!impl_->has_mesh || !(glm::length(dir) > 0)) return false;
  const auto h = impl_->surface().intersect_ray(impl_->mesh, origin, dir);
  if (h.face.is_valid() && hit) *hit = h.point;
  return h.face.is_valid();
}

void Session::grab_begin(const Point& center, double handle_radius, double roi_radius) {
  Impl& s = *impl_;
  s.require_mesh("grab");
  if (!(handle_radius >= 0) || !std::isfinite(handle_radius))
    throw std::invalid_argument("grab: 'handle_radius' must be a non-negative number");
  if (!(roi_radius > 0) || !std::isfinite(roi_radius))
    throw std::invalid_argument("grab: 'roi_radius' must be a positive number");
  s.end_grab();
  // The press is not a frame, but it should not cost the mesh either: the slot tree follows the
  // strokes and grabs (the vertex scan it replaces took 130 ms at 1.1M triangles; rebuilding an
  // AABB tree, 1 s at 2M triangles, at every press).
  Point picked;
  const mesh::Vertex near = s.locate_press(center, &picked);
  mesh::Face picked_face;  // a face at the vertex: the deformer's seed is the corner nearest the point
  for (mesh::Face f : s.mesh.faces(near)) {
    picked_face = f;
    break;
  }
  s.push_undo();
  s.grab.begin(s.mesh, picked, picked_face, handle_radius, roi_radius);
  // The kept remesher (made with the mesh; the slots of every stroke, grab, undo and redo since
  // reset) is in the state a new one starts in: the grab takes it with the scene's options instead
  // of a new remesher's pass over every edge (3 ms at the press at 1.1M triangles).
  // SculptRedraw.APullAfterAStrokeUndoneAndPulledAgainGivesTheSameMesh compares the two.
  if (s.remesher_kept) {
    s.remesher->set_options(s.options);
    s.remesher_kept = false;
  } else {
    s.make_remesher();
  }
  s.grabbing = true;
}

void Session::grab_drag(const deform::HandleTransform& total) {
  Impl& s = *impl_;
  if (!s.grabbing) throw std::logic_error("grab_drag: no grab in progress (call grab_begin first)");
  s.grab.drag(s.mesh, *s.remesher, total, s.options.epsilon, s.last, s.changes);
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
  if (!s.remesher_kept) {
    s.make_remesher();
  }
  s.remesher_kept = false;
  s.brushing = true;
}

void Session::brush_stamp(const Point& p, double pressure) {
  Impl& s = *impl_;
  if (!s.brushing) throw std::logic_error("brush_stamp: no stroke in progress (call brush_begin first)");
  const auto t0 = Clock::now();
  BrushFrame frame;
  s.note_changes();  // the stroke's locator syncs the slot tree while the list below is swapped out
  frame.touched.swap(s.changes.touched_vertices);  // appends without copying
  s.brush.sample(s.mesh, *s.remesher, p, pressure, frame);
  frame.touched.swap(s.changes.touched_vertices);
  if (frame.topology_changed) s.changes.topology_changed = true;
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

void Session::mask(const MaskOp& op) {
  Impl& s = *impl_;
  check_mask_op(op);
  if (mask_op_has_path(op.kind)) {
    mask_begin(op);
    for (const Point& p : op.path) mask_stamp(p);
    mask_end();
    return;
  }
  s.start_mask_step();
  s.mask_painter.apply_whole(s.mesh, op.kind, s.changes.touched_vertices);
  s.commit_step();
}

void Session::mask_begin(const MaskOp& op) {
  Impl& s = *impl_;
  check_mask_op(op, true);
  s.start_mask_step();
  s.mask_painter.begin_path(op);
  s.masking = true;
}

void Session::mask_stamp(const Point& p) {
  Impl& s = *impl_;
  if (!s.masking) throw std::logic_error("mask_stamp: no mask stroke in progress (call mask_begin first)");
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
    throw std::invalid_argument("mask: 'path' must hold finite points");
  auto locate = [&](const Point& q) {
    const geometry::FaceSlotTree::Hit hit = s.surface().closest_point(s.mesh, q);
    if (!hit.face.is_valid()) return mesh::Vertex();
    mesh::Vertex corners[3];
    s.mesh.face_vertices(hit.face, corners);
    return deform::walk_to_nearest_vertex(s.mesh, corners[0], q);
  };
  s.mask_painter.add_point(s.mesh, p, locate, s.changes.touched_vertices);
}

void Session::mask_end() { impl_->end_grab(); }
bool Session::masking() const { return impl_->masking; }

float Session::mask_value(mesh::Vertex v) const {
  const mesh::VertexProperty<float> m = mesh::find_mask(impl_->mesh);
  return m.is_valid() && v.idx < impl_->mesh.vertices_size() ? m[v] : 0.0f;
}

void Session::remesh(int iterations, double detail) {
  Impl& s = *impl_;
  s.require_mesh("remesh");
  if (iterations < 1) throw std::invalid_argument("remesh: 'iterations' must be a positive integer");
  if (!(detail >= 0) || !std::isfinite(detail))
    throw std::invalid_argument("remesh: 'detail' must be a non-negative length (0: the session's detail)");
  s.end_grab();
  const auto t0 = Clock::now();
  s.push_undo();
  remesh::RemeshOptions o = s.options;
  Impl::set_constant_detail(o, detail);
  o.projection = true;
  o.iterations = iterations;
  s.remesh_warning = remesh::remesh(s.mesh, o).warning;
  // Compacted in space order: the sculpting that follows walks fans, and a remeshed mesh's are
  // scattered over its arrays (mesh/surface_mesh.h). A whole-mesh step: every slot changes anyway.
  s.mesh.sort_in_space();
  s.history.commit_whole(s.mesh);
  s.journal.stop();  // a whole mesh is not an increment: the next save writes a full state
  s.last = FrameTimings{};
  s.last.remesh_ms = s.last.total_ms = ms_since(t0);
  s.mesh_replaced();
}

// Undo and redo swap the step's slots back (exact to the slot, see undo_log.h). A local step
// reports the vertices it touched, so the renderer updates only those; a whole-mesh step replaces
// everything.
bool Session::undo() { return impl_->step_history(true); }
bool Session::redo() { return impl_->step_history(false); }

bool Session::can_undo() const {
  return impl_->history.undo_steps() > 0 || impl_->grabbing || impl_->brushing || impl_->masking;
}
bool Session::can_redo() const {
  return impl_->history.redo_steps() > 0 && !impl_->grabbing && !impl_->brushing && !impl_->masking;
}

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
        remesh(step.count, step.detail);
        break;
      case SessionStep::Kind::Mask:
        mask(step.mask);
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

geometry::QualityReport Session::quick_quality() const {
  const Impl& s = *impl_;
  s.require_mesh("quality");
  s.note_changes();
  s.angle_figures.sync(s.mesh);
  geometry::QualityReport r;
  r.vertices = s.mesh.n_vertices();
  r.edges = s.mesh.n_edges();
  s.angle_figures.fill(r);
  return r;
}
const FrameTimings& Session::last_frame() const { return impl_->last; }

const std::string& Session::remesh_warning() const { return impl_->remesh_warning; }
const ChangeSet& Session::changes() const { return impl_->changes; }
void Session::clear_changes() {
  Impl& s = *impl_;
  if (s.grabbing || s.brushing || s.masking) s.move_step_touched();  // the step in progress still needs them when it ends
  s.note_changes();
  s.noted_vertices = s.noted_faces = 0;
  impl_->changes.topology_changed = false;
  impl_->changes.everything = false;
  impl_->changes.touched_vertices.clear();
  impl_->changes.touched_faces.clear();
  s.step_touched_from = 0;
}

std::vector<uint8_t> Session::export_bytes(io::Format f) const {
  impl_->require_mesh("export");
  return io::save_mesh_to_memory(impl_->mesh, f);
}

namespace {
// Ties change records to their full state: two tabs (or two saves) never share one.
std::uint64_t new_chain_id() {
  static std::uint64_t counter = 0;
  std::uint64_t x = std::uint64_t(std::chrono::system_clock::now().time_since_epoch().count()) ^ (++counter << 48);
  try {
    std::random_device rd;
    x ^= (std::uint64_t(rd()) << 32) ^ rd();
  } catch (...) {  // no entropy source: time and counter only
  }
  x += 0x9e3779b97f4a7c15ull;  // splitmix64's finaliser spreads the bits
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  x ^= x >> 31;
  return x ? x : 1;  // 0 means "no chain" (a version 2 state)
}
}  // namespace

std::vector<uint8_t> Session::save_state(size_t max_history_bytes) {
  Impl& s = *impl_;
  s.require_mesh("save state");
  if (s.grabbing || s.brushing || s.masking) throw std::logic_error("save state: a grab or a stroke is in progress");
  const std::uint64_t chain = new_chain_id();
  size_t n_undo = 0, n_redo = 0;
  std::vector<uint8_t> out =
      encode_session_state(s.state_settings(), s.mesh, s.history, max_history_bytes, chain, &n_undo, &n_redo);
  s.journal.start(chain, 0, n_undo, n_redo, out.size());
  return out;
}

std::optional<std::vector<uint8_t>> Session::save_changes() {
  Impl& s = *impl_;
  s.require_mesh("save changes");
  if (s.grabbing || s.brushing || s.masking) throw std::logic_error("save changes: a grab or a stroke is in progress");
  return s.journal.take(s.state_settings());
}

void Session::restore_state(const uint8_t* data, size_t size, const std::vector<ByteSpan>& changes) {
  DecodedState state = decode_session_state(data, size, kMaxUndoSteps, kMaxUndoBytes);
  for (size_t i = 0; i < changes.size(); ++i)
    apply_state_change(state, std::uint32_t(i + 1), changes[i].data, changes[i].size);
  remesh::RemeshOptions o = remesh::default_options_for(state.mesh);
  o.adaptive = true;
  o.epsilon = state.settings.epsilon;
  o.min_length = state.settings.min_length;
  o.max_length = state.settings.max_length;
  o.feature_angle_deg = state.settings.feature_angle_deg;
  try {
    remesh::check_options(o);
  } catch (const std::exception& e) {
    throw std::invalid_argument(std::string("saved state: ") + e.what());
  }
  // Everything checked: commit (moves only).
  Impl& s = *impl_;
  s.end_grab();
  s.drop_remesher();  // before the mesh it holds arrays on goes
  s.mesh = std::move(state.mesh);
  s.has_mesh = true;
  s.history = std::move(state.history);
  s.options = o;
  for (bool& rel : s.relative) rel = true;  // the blob holds lengths; the app's settings are percentages
  s.diagonal = state.settings.diagonal;
  s.last = FrameTimings{};
  s.mesh_replaced();
  // The session is what the saved records describe: later changes can go on as records after them.
  if (state.chain != 0)
    s.journal.start(state.chain, std::uint32_t(changes.size()), s.history.undo_steps(), s.history.redo_steps(), size);
  else
    s.journal.stop();
}

size_t Session::undo_steps() const { return impl_->history.undo_steps(); }
size_t Session::redo_steps() const { return impl_->history.redo_steps(); }
size_t Session::memory_bytes() const {
  const Impl& s = *impl_;
  if (!s.has_mesh) return 0;
  return s.history.shadow_bytes() * 2 + s.history.history_bytes();  // the mesh is as large as its shadow
}

void Session::set_history_verification(bool on) { impl_->history.set_verify(on); }
const std::vector<mesh::Vertex>* Session::mirror_map(int axis) {
  Impl& s = *impl_;
  s.require_mesh("mirror_map");
  s.end_grab();
  return s.mirror.map(s.mesh, axis);
}
size_t Session::mirror_settled() const { return impl_->mirror.last_settled(); }
void Session::set_mirror_tracking(bool on) { impl_->mirror_tracking = on; }
const std::vector<mesh::Edge>* Session::unpaired_mirror_features(int axis) {
  Impl& s = *impl_;
  s.require_mesh("unpaired_mirror_features");
  s.end_grab();
  s.mirror_axis_hint = axis;
  if (!(s.options.feature_angle_deg > 0) || !s.lend_mirror_map_once()) return nullptr;
  return s.remesher->mirror_unpaired_features();
}

size_t Session::history_full_diffs() const { return impl_->history.full_diffs(); }

}  // namespace adasculpt::sculpt
