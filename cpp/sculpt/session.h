#pragma once
// Session: the one stateful object of the core. It owns the mesh, the remeshing settings, the
// grab in progress and the undo history, and reports what each call changed and how long the
// last frame took. The CLI (replay), the wasm bindings and the tests all drive the core through it.
//
// Undo model: every grab (grab_begin .. grab_end), every brush stroke (brush_begin .. brush_end)
// and every whole-mesh remesh() is one undo step, recorded in an UndoLog (undo_log.h): a grab or a
// stroke keeps the bytes of the slots it changed (memory in proportion to the changed region), a
// whole remesh keeps the mesh before it. Undo and redo are exact to the slot: positions,
// connectivity, deleted slots and numbering come back bit for bit. The history is bounded
// (kMaxUndoSteps steps and kMaxUndoBytes bytes; the oldest steps are dropped first).
// A mask operation (mask()) is a step too.
//
// The mesh may contain deleted slots, and readers must skip them (mesh().is_deleted(...)): grabs
// and strokes never compact it, since the history refers to slots (load, restore_state and a
// whole remesh() start a compact numbering; changes() then reports everything).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "deform/handle_deformer.h"
#include "deform/handle_transform.h"
#include "geometry/quality.h"
#include "io/mesh_io.h"
#include "mesh/surface_mesh.h"
#include "sculpt/brush.h"
#include "sculpt/mask.h"

namespace adasculpt::sculpt {

// Milliseconds spent in each phase of the last grab_drag() frame (or of the last remesh() or
// brush_stamp(): roi = finding the surface under the brush, summed over its `stamps`).
// A grab frame also says whether its ROI was cut to the vertex budget (roi_capped; the user
// should be told) and how many vertices the ROI holds (handle + free).
struct FrameTimings {
  double roi_ms = 0, field_ms = 0, refine_ms = 0, deform_ms = 0, remesh_ms = 0, total_ms = 0;
  int stamps = 0;
  bool roi_capped = false;
  int roi_vertices = 0;
  // A grab frame: it applied a finished exact solve of the field (the field's refreshes).
  bool field_refreshed = false;
  // A grab frame: the vertices its remeshing iteration worked on (the strained part of the
  // region and two rings, sculpt/region_strain.h).
  int remeshed_vertices = 0;
  // A grab frame's mesh edits: the refinement's splits, then the region iteration's.
  int refine_splits = 0, splits = 0, collapses = 0, flips = 0;
};

// What changed since the last clear_changes(). topology_changed: faces or vertices were added or
// removed (renderers must re-read indices); everything: re-read the whole mesh (load, undo,
// redo, whole remesh). touched_vertices: vertices whose positions may have changed (no duplicates
// guaranteed only per frame; may contain vertices deleted since). touched_faces: face slots
// deleted by the remesher's collapses, or rewritten by an undo/redo, since then (duplicates
// possible). Together with the faces around the touched vertices and the slots appended, they
// are every face slot whose triangle may have changed, so a renderer keeping one triangle per
// slot updates in proportion to the change (sculpt/render_buffers.h).
struct ChangeSet {
  bool topology_changed = false;
  bool everything = false;
  std::vector<mesh::Vertex> touched_vertices;
  std::vector<mesh::Face> touched_faces;
};

class Session {
 public:
  static constexpr size_t kMaxUndoSteps = 64;
  static constexpr size_t kMaxUndoBytes = size_t(512) << 20;

  Session();
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // Replaces the mesh; resets the history and the settings (defaults relative to the new
  // bounding-box diagonal: epsilon 0.05%, min 0.2%, max 5%, features off). Ends any grab.
  // `warnings`: the repairs the reader made to get `mesh` (load_warnings()).
  void load(mesh::SurfaceMesh mesh, std::vector<std::string> warnings = {});
  // io::load_mesh_from_memory; on error throws and keeps the current mesh.
  void load_bytes(const uint8_t* data, size_t size, const std::string& name_hint);
  void load_file(const std::string& path);
  // What the reader repaired in the last load (faces reversed to one orientation, non-manifold
  // vertices split, unreferenced vertices dropped...), one sentence each; empty when nothing.
  const std::vector<std::string>& load_warnings() const;
  bool has_mesh() const;
  const mesh::SurfaceMesh& mesh() const;

  // Keys: epsilon, min_length, max_length (number = absolute length, or a string "0.05%" =
  // percent of the bounding-box diagonal), features (dihedral angle in degrees, 0 = off),
  // guard_crossings (true: sculpting's remeshing creates no crossing triangles, at about 1.6x the
  // frame cost; off by default, kept through loads).
  // Unknown keys and bad values throw std::invalid_argument naming the field; on error nothing
  // changes. Keys not given keep their current value. A brush stroke applies the percentages (and
  // the defaults) to the connected component under the brush: scaled by its bounding-box
  // diagonal over the scene's (on a mesh of one piece, as given), so that loading more objects
  // does not coarsen the detail of each; lengths given as numbers stay as given. A stroke's own
  // `detail` (BrushSettings) replaces them.
  void set_settings(const nlohmann::json& s);
  // {"epsilon":..., "min_length":..., "max_length":..., "features":..., "guard_crossings":...,
  // "diagonal":...} (lengths absolute).
  nlohmann::json settings() const;

  // Ray against the current surface; *hit = first intersection. False when nothing is hit.
  bool pick(const Point& origin, const Vec3& dir, Point* hit) const;

  // Starts a grab at the surface point closest to center (geodesic radii, absolute lengths).
  // Throws std::invalid_argument on non-positive radii or without a mesh; ends a running grab first.
  void grab_begin(const Point& center, double handle_radius, double roi_radius);
  // One frame: `total` is the transform since grab_begin. ROI + field, refinement, deformation
  // by the increment since the last frame, one remeshing iteration on the ROI plus a ring.
  void grab_drag(const deform::HandleTransform& total);
  // Ends the grab (one undo step); compacts the mesh when deleted slots add up (see above).
  void grab_end();
  bool grabbing() const;
  // How a grab solves its field (carried, or every frame as in the paper) and the ROI's vertex
  // budget (deform/handle_deformer.h); changes apply from the next grab_begin.
  deform::DeformOptions& grab_options();

  // Brush strokes (sculpt/brush.h). brush_begin ends a running grab or stroke and starts one undo
  // step; throws std::invalid_argument on bad settings or without a mesh. Each brush_stamp is one
  // pointer sample (a surface point, or for grab the pointer position in space); it runs the
  // stamps due since the previous sample, each followed by one remeshing iteration on the
  // brushed vertices plus a ring. brush_end ends the stroke as grab_end ends a grab.
  void brush_begin(const deform::BrushSettings& settings);
  void brush_stamp(const Point& p, double pressure = 1);
  void brush_end();
  bool brushing() const;
  // begin, one stamp call per path point, end: one undo step.
  void brush_stroke(const BrushStroke& stroke);

  // A mask operation (sculpt/mask.h): one undo step. Ends a running grab or stroke; throws
  // std::invalid_argument on a bad operation or without a mesh. The first one gives the mesh its
  // mask (mesh/vertex_mask.h), which then follows every edit, undo, redo and the saved state.
  // Fully masked vertices never move under a brush or a grab, and no remeshing touches their
  // triangles; partly masked ones move by (1 - mask) of what they would.
  void mask(const MaskOp& op);
  // A paint or erase stroke as the pointer moves, one undo step: mask_begin (op.path not read),
  // one mask_stamp per pointer sample (a surface point), mask_end. mask(op) with a path does the
  // same in one call. Grabs, brush strokes, undo and redo end a running mask stroke first.
  void mask_begin(const MaskOp& op);
  void mask_stamp(const Point& p);
  void mask_end();
  bool masking() const;
  // The mask value of every vertex slot (0 for all without a mask).
  float mask_value(mesh::Vertex v) const;

  // Whole-mesh adaptive remeshing with projection onto the current surface; one undo step.
  // detail > 0: every edge towards that absolute length instead of the settings (the detail flood
  // fill: the whole mesh at a stroke's constant detail).
  void remesh(int iterations, double detail = 0);
  // Empty, or one line for the user when the last remesh() stopped at its vertex limit (the mesh
  // is the valid one reached so far; remesh::RemeshReport::warning).
  const std::string& remesh_warning() const;

  bool undo();
  bool redo();
  bool can_undo() const;
  bool can_redo() const;

  // Runs a session file ({"version":1,"settings":{...},"steps":[...]}, see session_file.h) on
  // the current mesh and returns the report JSON (frames, frame_ms_median/p95/max, per-phase
  // medians, vertices, faces, min_angle_deg, mean_min_angle_deg). Throws std::invalid_argument
  // for invalid files before running anything.
  nlohmann::json replay(const nlohmann::json& session_file);

  // The whole report: a pass over the mesh (895 ms at 1.1M triangles in the browser), for reports
  // and on request, not after every stroke.
  geometry::QualityReport quality() const;
  // What a viewer shows after every stroke, kept up to date from the changes so that it costs what
  // changed, not the mesh (geometry/angle_figures.h): vertices, faces, edges and the angle figures
  // (min/max angle, mean min angle, shares under 30 and 10 degrees) as quality() gives them; the
  // other fields stay 0.
  geometry::QualityReport quick_quality() const;
  const FrameTimings& last_frame() const;
  const ChangeSet& changes() const;
  void clear_changes();
  std::vector<uint8_t> export_bytes(io::Format f) const;

  // The whole state in one lossless binary blob, for autosave: the current mesh as its slots
  // (positions, connectivity, deletion marks), the settings (absolute, with the diagonal they were
  // made relative to) and the undo/redo history, newest undo steps first, then the nearest redo
  // steps, as many as fit in max_history_bytes (serialized size; the current mesh is always
  // included). Everything comes back bit for bit, slot numbering included. Throws
  // std::logic_error without a mesh or during a grab/stroke.
  // Each full state starts a chain of change records (save_changes).
  static constexpr size_t kDefaultStateHistoryBytes = size_t(96) << 20;
  std::vector<uint8_t> save_state(size_t max_history_bytes = kDefaultStateHistoryBytes);
  // Incremental autosave (state_changes.h): the changes since the last save_state/save_changes (new
  // undo steps, each the size of its changed region, undos, redos, the settings) as one small
  // record, the next of the chain. nullopt when they cannot be a record (nothing saved or restored
  // yet, a load or whole remesh since, an undo past the history the full state kept, or records
  // adding up to the full state's size): then save_state() is due. Throws as save_state.
  std::optional<std::vector<uint8_t>> save_changes();
  // Replaces mesh, settings and history with a save_state() blob followed by its change records
  // (in order, the first after the blob first): the session ends where the last record was saved,
  // with the same undo/redo history. All or nothing: a truncated or corrupt blob or record (a mesh
  // or any state the history reaches that is not a valid surface, a record of another chain or out
  // of order) throws std::invalid_argument("saved state: ...") and nothing changes. Ends any grab.
  // Checking visits every state the history holds (a swap of the changed slots and a validate()
  // per step). Later save_changes() records continue the same chain.
  struct ByteSpan {
    const uint8_t* data;
    size_t size;
  };
  void restore_state(const uint8_t* data, size_t size, const std::vector<ByteSpan>& changes = {});
  // Undo and redo steps held, and the rough heap size of the mesh, the history's copy of it
  // (undo_log.h: the shadow) and the history (bytes).
  size_t undo_steps() const;
  size_t redo_steps() const;
  size_t memory_bytes() const;
  // For tests: compare the history's whole copy of the mesh after every change (O(mesh) each),
  // and how often a step had to compare the whole mesh to find its changes (0 when every change
  // stayed near the touched vertices, as strokes and grabs do).
  void set_history_verification(bool on);
  size_t history_full_diffs() const;
  // The mirror map the next symmetric stroke across `axis` takes (geometry::find_mirror_map's
  // answer, kept up to date through every change at its cost: geometry::MirrorTracker), nullptr
  // when the mesh is not exactly symmetric; and how many vertices that answer had to settle.
  // Tracking off (tests): every symmetric stroke searches the whole mesh, as before.
  const std::vector<mesh::Vertex>* mirror_map(int axis);
  size_t mirror_settled() const;
  void set_mirror_tracking(bool on);
  // Tests: with features on and a map across `axis`, the feature edges whose image is no edge or
  // no feature, as the strokes' remesher finds them from the changes since its last check
  // (Remesher::note_mirror_changes); nullptr without features, a map or a mask its own image.
  const std::vector<mesh::Edge>* unpaired_mirror_features(int axis);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace adasculpt::sculpt
