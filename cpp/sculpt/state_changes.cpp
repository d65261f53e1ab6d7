#include "sculpt/state_changes.h"

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "mesh/vertex_mask.h"
#include "sculpt/byte_io.h"

namespace adasculpt::sculpt {

namespace {
constexpr char kChangeMagic[8] = {'A', 'D', 'S', 'C', 'C', 'H', 'N', 'G'};
constexpr std::uint32_t kChangeVersion = 1;
enum Event : std::uint8_t { kCommit = 0, kUndo = 1, kRedo = 2 };

// FNV-1a over the record: a flipped byte in a position or a value would otherwise restore a valid
// but different mesh (records are small, so this costs well under a millisecond).
std::uint64_t checksum(const std::uint8_t* p, size_t n) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  return h;
}

// The mesh a replayed commit produced, checked as read_history checks the states it reaches.
void check_mesh(const mesh::SurfaceMesh& m) {
  try {
    m.validate();
  } catch (const std::logic_error& e) {
    byte_io::fail(std::string("a change record: ") + e.what());
  }
  for (mesh::Vertex v : m.vertices()) {
    const Point& q = m.position(v);
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
      byte_io::fail("a change record: non-finite position");
  }
  // As read_history: a mask value outside [0, 1] would let a brush push a vertex the wrong way.
  if (const mesh::VertexProperty<float> mask = mesh::find_mask(m); mask.is_valid())
    for (mesh::Vertex v : m.vertices())
      if (!(mask[v] >= 0.0f && mask[v] <= 1.0f)) byte_io::fail("a change record: a mask value outside [0, 1]");
}
}  // namespace

void ChangeJournal::start(std::uint64_t chain, std::uint32_t sequence, size_t n_undo, size_t n_redo,
                          size_t cap_bytes) {
  active_ = true;
  chain_ = chain;
  sequence_ = sequence;
  undo_ = n_undo;
  redo_ = n_redo;
  cap_ = cap_bytes;
  events_.clear();
  n_events_ = 0;
}

void ChangeJournal::stop() {
  active_ = false;
  events_.clear();
  events_.shrink_to_fit();  // a stopped journal holds nothing until the next full state
  n_events_ = 0;
}

void ChangeJournal::commit(const UndoLog& log, const mesh::SurfaceMesh& m) {
  if (!active_) return;
  byte_io::put(events_, std::uint8_t(kCommit));
  byte_io::put(events_, std::uint32_t(log.undo_steps()));
  if (!log.write_newest_for_replay(m, events_) || events_.size() > cap_) {
    stop();  // a whole-mesh step, or more than a full state would be
    return;
  }
  ++n_events_;
  undo_ = std::min(undo_ + 1, log.undo_steps());  // the writer's limits dropped the oldest: the reader drops as many
  redo_ = 0;
}

void ChangeJournal::undo() {
  if (!active_) return;
  if (undo_ == 0) return stop();  // the step is older than the full state kept
  byte_io::put(events_, std::uint8_t(kUndo));
  ++n_events_;
  --undo_;
  ++redo_;
}

void ChangeJournal::redo() {
  if (!active_) return;
  if (redo_ == 0) return stop();
  byte_io::put(events_, std::uint8_t(kRedo));
  ++n_events_;
  ++undo_;
  --redo_;
}

std::optional<std::vector<std::uint8_t>> ChangeJournal::take(const StateSettings& settings) {
  if (!active_) return std::nullopt;
  std::vector<std::uint8_t> out;
  out.reserve(64 + events_.size());
  for (char c : kChangeMagic) out.push_back(std::uint8_t(c));
  byte_io::put(out, kChangeVersion);
  byte_io::put(out, chain_);
  byte_io::put(out, ++sequence_);
  write_state_settings(settings, out);
  byte_io::put(out, n_events_);
  out.insert(out.end(), events_.begin(), events_.end());
  byte_io::put(out, std::uint32_t(undo_));
  byte_io::put(out, std::uint32_t(redo_));
  byte_io::put(out, checksum(out.data(), out.size()));
  events_.clear();
  n_events_ = 0;
  return out;
}

void apply_state_change(DecodedState& state, std::uint32_t sequence, const std::uint8_t* data, size_t size) {
  if (size < 16 || std::memcmp(data, kChangeMagic, 8) != 0) byte_io::fail("not an adasculpt change record (bad magic)");
  std::uint64_t sum;
  std::memcpy(&sum, data + size - 8, 8);
  if (sum != checksum(data, size - 8)) byte_io::fail("a change record is damaged (checksum)");
  const std::uint8_t* p = data + 8;
  size_t left = size - 16;
  byte_io::Reader r{p, left};
  const std::uint32_t version = r.get<std::uint32_t>();
  if (version != kChangeVersion) byte_io::fail("unsupported change record version " + std::to_string(version));
  const std::uint64_t chain = r.get<std::uint64_t>();
  if (state.chain == 0 || chain != state.chain) byte_io::fail("a change record of another saved state");
  const std::uint32_t seq = r.get<std::uint32_t>();
  if (seq != sequence)
    byte_io::fail("change record " + std::to_string(seq) + " where " + std::to_string(sequence) + " belongs");
  const StateSettings settings = read_state_settings(p, left);
  const std::uint32_t n = r.get<std::uint32_t>();
  if (n > left) byte_io::fail("truncated change record");
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint8_t e = r.get<std::uint8_t>();
    if (e == kCommit) {
      const std::uint32_t keep = r.get<std::uint32_t>();
      state.history.replay_commit(state.mesh, p, left, keep);
      check_mesh(state.mesh);
    } else if (e == kUndo || e == kRedo) {
      // Both states of a step the history held were validated when it was read or replayed.
      const bool done = e == kUndo ? state.history.undo(state.mesh, nullptr, nullptr)
                                   : state.history.redo(state.mesh, nullptr, nullptr);
      if (!done) byte_io::fail(e == kUndo ? "an undo past the saved history" : "a redo past the saved history");
    } else {
      byte_io::fail("unknown change event " + std::to_string(e));
    }
  }
  const std::uint32_t n_undo = r.get<std::uint32_t>(), n_redo = r.get<std::uint32_t>();
  if (n_undo != state.history.undo_steps() || n_redo != state.history.redo_steps())
    byte_io::fail("a change record leaves another history than it says");
  if (left != 0) byte_io::fail(std::to_string(left) + " unexpected bytes at the end of a change record");
  state.settings = settings;
}

}  // namespace adasculpt::sculpt
