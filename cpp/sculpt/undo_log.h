#pragma once
// UndoLog: the undo/redo history as a log of slot changes (the idea of Blender's BMLog, on this
// project's array-of-slots mesh). A step records, for the slots it changed, the bytes of every
// property array before it; undo swaps those bytes back in and truncates the arrays to their
// sizes before the step (a step never removes slots: deletion only marks them, and the mesh is
// not compacted while the history refers to slots); redo swaps again and regrows them. Memory per
// step is proportional to the changed region, and undo is exact to the slot: positions,
// connectivity, deletion marks, slot numbering and every property come back bit for bit.
//
// Finding the changed slots without a pass over the mesh: the log keeps a "shadow", a copy of the
// mesh as it was when the current step began (one extra mesh, not one per step). At the step's
// end only the slots around the step's touched vertices are compared with the shadow: the
// vertices, their one-rings in the old and the new connectivity, the vertices deleted in a chain
// from them, and the edges, halfedges and faces around all those; the slots the step appended are
// taken whole (two rings: one ring missed a position in a mirrored snake-hook stroke of the random
// test). Every deletion must show up there: the number of deletions found is checked
// against the mesh's deletion counters, and a mismatch falls back to comparing everything (counted
// in full_diffs(), which the tests require to stay 0 for strokes and grabs). set_verify(true)
// compares the whole shadow after every change (tests).
//
// Whole-mesh steps (a remesh of everything) keep the mesh before them whole: the shadow itself
// moves into the step, and undo swaps meshes.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "mesh/surface_mesh.h"

namespace adasculpt::sculpt {

class UndoLog {
 public:
  static constexpr int kKinds = 4;  // vertices, halfedges, edges, faces

  UndoLog();
  ~UndoLog();
  UndoLog(UndoLog&&) noexcept;
  UndoLog& operator=(UndoLog&&) noexcept;

  // Forgets the history; `m` becomes the state steps start from (the shadow is a copy of it).
  void reset(const mesh::SurfaceMesh& m);
  // The mesh changed only around `touched` (vertices whose positions or incident elements changed,
  // duplicates and deleted ones allowed) since the last reset/commit/undo/redo: one undo step.
  // Drops the redo steps. A step that changed nothing is still a step (undo takes back "the
  // stroke", as the user sees it).
  bool commit_local(const mesh::SurfaceMesh& m, const std::vector<mesh::Vertex>& touched);
  // Any change at all (a whole-mesh remesh, compaction): one step holding the mesh before it.
  void commit_whole(const mesh::SurfaceMesh& m);
  // Between steps, after the mesh got a new logged array (the mask, mesh/vertex_mask.h): the
  // shadow gets a copy, so the next step records that array's changes too. Steps recorded before
  // do not hold it and leave it alone on undo.
  void adopt_new_arrays(const mesh::SurfaceMesh& m);

  // Undo/redo the newest step. `touched` receives the vertices whose position or incident faces
  // changed and `faces` (when given) the face slots the step rewrote or brought back, deleted
  // ones included (for the render buffers: a face the step deletes again is reachable from no
  // vertex); *whole is set when the step replaced the whole mesh (then readers must start over).
  // False when there is no step.
  bool undo(mesh::SurfaceMesh& m, std::vector<mesh::Vertex>* touched, bool* whole,
            std::vector<mesh::Face>* faces = nullptr);
  bool redo(mesh::SurfaceMesh& m, std::vector<mesh::Vertex>* touched, bool* whole,
            std::vector<mesh::Face>* faces = nullptr);

  // The vertex slots the last commit_local, undo or redo changed in any array (positions,
  // connectivity, deletion marks, the mask), deleted ones and the slots appended included (slots an
  // undo cut off are past the mesh's end); nullptr after a whole-mesh step (everything changed).
  // Unlike `touched`, it holds the vertices a step deleted: a mirror map must learn of them.
  const std::vector<mesh::Vertex>* last_changed_vertices() const {
    return changed_known_ ? &changed_vertices_ : nullptr;
  }

  size_t undo_steps() const { return undo_.size(); }
  size_t redo_steps() const { return redo_.size(); }
  // Bounds: at most max_steps undo steps and max_bytes of them (the oldest go first; the newest
  // step is always kept).
  void set_limits(size_t max_steps, size_t max_bytes);
  size_t history_bytes() const;  // undo + redo steps
  size_t shadow_bytes() const;
  size_t full_diffs() const { return full_diffs_; }
  void set_verify(bool on) { verify_ = on; }

  // ---- persistence (Session::save_state). A step serializes itself with both states' values (a
  // journal entry replays it on a mesh in its "before" state) or, for the saved history, in the
  // form it is held in. Slots are written raw; readers validate the resulting meshes.
  struct Step;
  // The steps, oldest undo first, then redo steps from the farthest to the nearest.
  const std::deque<std::unique_ptr<Step>>& undo_list() const { return undo_; }
  const std::deque<std::unique_ptr<Step>>& redo_list() const { return redo_; }
  static void write_step(const Step& s, std::vector<std::uint8_t>& out);
  static size_t step_serialized_size(const Step& s);
  // Reads n_undo + n_redo steps written by write_step (same order as the lists) and makes them the
  // history, `m` being the current mesh. Every state the steps reach is built and validated first
  // (undo all the way back, then redo all the way forward); malformed bytes or a bad step throw
  // std::invalid_argument and leave `m` and the log as they were.
  void read_history(mesh::SurfaceMesh& m, const std::uint8_t*& p, size_t& left, std::uint32_t n_undo,
                    std::uint32_t n_redo);

  // ---- incremental autosave (state_changes.h). The newest undo step written in its redo form (the
  // values of its slots after it, taken from `m`, which must be the state right after the commit),
  // so that a reader holding the state before it can replay it. False, writing nothing, when there
  // is no step or it is a whole-mesh step (a whole mesh is not an increment).
  bool write_newest_for_replay(const mesh::SurfaceMesh& m, std::vector<std::uint8_t>& out) const;
  // Replays such a record as the commit it was: drops the redo steps, redoes the step on `m` and
  // then drops the oldest undo steps past keep_undo (the writer's count after the commit, so the
  // limits trim as they did there). A step that does not fit `m` throws std::invalid_argument
  // before changing anything; the caller validates the resulting mesh.
  void replay_commit(mesh::SurfaceMesh& m, const std::uint8_t*& p, size_t& left, size_t keep_undo);

 private:
  static std::unique_ptr<Step> read_step(const std::uint8_t*& p, size_t& left);
  bool swap_step(Step& s, mesh::SurfaceMesh& m, std::vector<mesh::Vertex>* touched, bool* whole,
                 std::vector<mesh::Face>* faces);
  void sync_arrays(mesh::SurfaceMesh& m);
  void enforce_limits();
  void note_changed_vertices(const std::vector<std::uint32_t>& slots, size_t appended_from, size_t appended_to);
  void check_shadow(const mesh::SurfaceMesh& m) const;

  std::unique_ptr<mesh::SurfaceMesh> shadow_;
  std::deque<std::unique_ptr<Step>> undo_, redo_;
  size_t undo_bytes_ = 0;
  size_t max_steps_ = 64, max_bytes_ = size_t(512) << 20;
  size_t full_diffs_ = 0;
  bool verify_ = false;
  // Scratch for commit_local: candidate slots per kind, deduplicated with per-slot stamps.
  std::vector<std::uint32_t> candidates_[kKinds];
  std::vector<std::uint32_t> stamp_[kKinds];
  std::uint32_t epoch_ = 0;
  std::vector<mesh::Vertex> changed_vertices_;
  bool changed_known_ = false;
};

// A whole mesh as its slots (positions, connectivity, deletion marks: deleted slots and numbering
// included), for the saved state; reading validates it and throws std::invalid_argument.
void write_mesh_slots(const mesh::SurfaceMesh& m, std::vector<std::uint8_t>& out);
size_t mesh_slots_serialized_size(const mesh::SurfaceMesh& m);
mesh::SurfaceMesh read_mesh_slots(const std::uint8_t*& p, size_t& left);

}  // namespace adasculpt::sculpt
