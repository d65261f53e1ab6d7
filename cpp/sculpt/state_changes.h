#pragma once
// Incremental autosave: after a full saved state (session_state.h), the changes since it as small
// records, so that saving one stroke costs the stroke's region, not the mesh. The Session keeps a
// ChangeJournal: every new undo step is written (in the form that replays it) when it is
// committed, undo and redo are one byte each; save_changes() hands out what gathered as one
// record. A reader restores the full state, then applies the records in order (apply_state_change),
// which replays the same commits, undos and redos and ends in the same mesh with the same history.
//
//   "ADSCCHNG" u32 version=1, u64 chain id (the full state's), u32 sequence (1, 2, ... after it),
//   settings (5 f64, as in the full state), u32 event count, events, u32 undo count, u32 redo count
//   (the reader's history after the record, checked), u64 FNV-1a of everything before it.
//   Event: u8 0 = commit, u32 undo steps the writer kept after it (its limits dropped the oldest),
//   the step (UndoLog::write_newest_for_replay);
//   u8 1 = undo; u8 2 = redo.
//
// The reader holds the newest undo steps and nearest redo steps the full state kept (its byte
// budget may leave old ones out), so the journal follows that history's counts, not the live one's:
// an undo or redo beyond it, or a whole-mesh step (a remesh), cannot be a record, and the journal
// stops; save_changes() then says a full state is needed.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "mesh/surface_mesh.h"
#include "sculpt/session_state.h"
#include "sculpt/undo_log.h"

namespace adasculpt::sculpt {

class ChangeJournal {
 public:
  // A full state was written (or restored) holding n_undo undo and n_redo redo steps; records
  // follow it from `sequence` + 1. The pending events are bounded by cap_bytes (past it the
  // journal stops: writing the full state again costs about as much).
  void start(std::uint64_t chain, std::uint32_t sequence, size_t n_undo, size_t n_redo, size_t cap_bytes);
  void stop();
  bool active() const { return active_; }
  // After UndoLog::commit_local / commit_whole, undo, redo of the live history.
  void commit(const UndoLog& log, const mesh::SurfaceMesh& m);
  void undo();
  void redo();
  // The record of everything since the last one (settings included); nullopt when the journal is
  // stopped (then a full state must be written).
  std::optional<std::vector<std::uint8_t>> take(const StateSettings& settings);
  std::uint32_t sequence() const { return sequence_; }

 private:
  bool active_ = false;
  std::uint64_t chain_ = 0;
  std::uint32_t sequence_ = 0;
  size_t undo_ = 0, redo_ = 0;  // the reader's history counts after the pending events
  size_t cap_ = 0;
  std::vector<std::uint8_t> events_;
  std::uint32_t n_events_ = 0;
};

// Applies one record to a decoded state (mesh, history and settings are replaced as the record
// says). The record must carry the state's chain id and the sequence number `sequence`. Every mesh
// a commit produces is validated; a damaged or foreign record throws std::invalid_argument("saved
// state: ...") and may leave `state` half changed (the caller works on a copy it can drop).
void apply_state_change(DecodedState& state, std::uint32_t sequence, const std::uint8_t* data, size_t size);

}  // namespace adasculpt::sculpt
