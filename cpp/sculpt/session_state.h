#pragma once
// The Session's saved state (Session::save_state / restore_state): the remesh settings, the mesh
// as slots and the undo/redo history as the undo log's steps, in one little-endian blob. This file
// owns the format; the Session only gathers what goes in and commits what comes out.
//
//   "ADSCSTAT" u32 version=3, u64 chain id (version 3 only; 0 when read from version 2), f64 epsilon
//   min_length max_length features diagonal,
//   u32 undo count, u32 redo count, the current mesh as slots (undo_log.h: write_mesh_slots),
//   then the steps (UndoLog::write_step): undo steps oldest..newest, redo steps farthest..nearest.
// The chain id ties the change records written after this state (state_changes.h) to it.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mesh/surface_mesh.h"
#include "sculpt/undo_log.h"

namespace adasculpt::sculpt {

// The settings the state carries, as absolute lengths (the app's percentages are re-derived from
// the diagonal on restore).
struct StateSettings {
  double epsilon = 0, min_length = 0, max_length = 0, feature_angle_deg = 0, diagonal = 0;
};

// The settings as five f64, and back (checks the diagonal and min <= max; throws "saved state: ...").
void write_state_settings(const StateSettings& s, std::vector<std::uint8_t>& out);
StateSettings read_state_settings(const std::uint8_t*& p, size_t& left);

// The blob for `mesh` and `history`: the newest undo steps first, then the nearest redo steps,
// while they fit max_history_bytes (the rest of the history is left out, oldest first).
// *n_undo / *n_redo (when given) receive how many steps went in.
std::vector<std::uint8_t> encode_session_state(const StateSettings& settings, const mesh::SurfaceMesh& mesh,
                                               const UndoLog& history, size_t max_history_bytes,
                                               std::uint64_t chain = 0, size_t* n_undo = nullptr,
                                               size_t* n_redo = nullptr);

struct DecodedState {
  StateSettings settings;
  mesh::SurfaceMesh mesh;
  UndoLog history;
  std::uint64_t chain = 0;
};
// Reads and validates a blob: every mesh the history reaches is built and checked. A damaged or
// foreign blob throws std::invalid_argument("saved state: ..."). The history gets the given limits.
// The settings are read as stored; the caller checks them as remesh options.
DecodedState decode_session_state(const std::uint8_t* data, size_t size, size_t max_undo_steps,
                                  size_t max_undo_bytes);

}  // namespace adasculpt::sculpt
