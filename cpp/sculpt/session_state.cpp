#include "sculpt/session_state.h"

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "sculpt/byte_io.h"

namespace adasculpt::sculpt {

namespace {
constexpr char kStateMagic[8] = {'A', 'D', 'S', 'C', 'S', 'T', 'A', 'T'};
constexpr std::uint32_t kStateVersion = 3;  // 2: the same without the chain id (still read)

bool little_endian_host() {
  const std::uint32_t probe = 1;
  std::uint8_t first;
  std::memcpy(&first, &probe, 1);
  return first == 1;
}
}  // namespace

void write_state_settings(const StateSettings& s, std::vector<std::uint8_t>& out) {
  for (double x : {s.epsilon, s.min_length, s.max_length, s.feature_angle_deg, s.diagonal}) byte_io::put(out, x);
}

StateSettings read_state_settings(const std::uint8_t*& p, size_t& left) {
  byte_io::Reader r{p, left};
  StateSettings s;
  for (double* x : {&s.epsilon, &s.min_length, &s.max_length, &s.feature_angle_deg, &s.diagonal})
    *x = r.get<double>();
  if (!(s.diagonal > 0) || !std::isfinite(s.diagonal)) byte_io::fail("bad diagonal");
  if (!(s.min_length <= s.max_length)) byte_io::fail("'min_length' exceeds 'max_length'");
  return s;
}

std::vector<std::uint8_t> encode_session_state(const StateSettings& settings, const mesh::SurfaceMesh& mesh,
                                               const UndoLog& history, size_t max_history_bytes,
                                               std::uint64_t chain, size_t* n_undo_out, size_t* n_redo_out) {
  if (!little_endian_host()) throw std::logic_error("save state: big-endian host");
  // Undo steps apply in order from the newest, so the kept ones are the newest run; likewise redo.
  const auto& undo = history.undo_list();
  const auto& redo = history.redo_list();
  size_t used = 0, n_undo = 0, n_redo = 0;
  for (auto it = undo.rbegin(); it != undo.rend(); ++it, ++n_undo) {
    const size_t b = UndoLog::step_serialized_size(**it);
    if (used + b > max_history_bytes) break;
    used += b;
  }
  if (n_undo == undo.size())
    for (auto it = redo.rbegin(); it != redo.rend(); ++it, ++n_redo) {
      const size_t b = UndoLog::step_serialized_size(**it);
      if (used + b > max_history_bytes) break;
      used += b;
    }
  std::vector<std::uint8_t> out;
  out.reserve(64 + mesh_slots_serialized_size(mesh) + used);
  for (char c : kStateMagic) out.push_back(std::uint8_t(c));  // (vector::insert of the char range trips a g++ 12 false -Wstringop-overflow)
  byte_io::put(out, kStateVersion);
  byte_io::put(out, chain);
  write_state_settings(settings, out);
  byte_io::put(out, std::uint32_t(n_undo));
  byte_io::put(out, std::uint32_t(n_redo));
  write_mesh_slots(mesh, out);
  for (size_t i = undo.size() - n_undo; i < undo.size(); ++i) UndoLog::write_step(*undo[i], out);
  for (size_t i = redo.size() - n_redo; i < redo.size(); ++i) UndoLog::write_step(*redo[i], out);
  if (n_undo_out) *n_undo_out = n_undo;
  if (n_redo_out) *n_redo_out = n_redo;
  return out;
}

DecodedState decode_session_state(const std::uint8_t* data, size_t size, size_t max_undo_steps,
                                  size_t max_undo_bytes) {
  if (size < 8 || std::memcmp(data, kStateMagic, 8) != 0) byte_io::fail("not an adasculpt state (bad magic)");
  const std::uint8_t* p = data + 8;
  size_t left = size - 8;
  byte_io::Reader r{p, left};
  const std::uint32_t version = r.get<std::uint32_t>();
  if (version != kStateVersion && version != 2) byte_io::fail("unsupported version " + std::to_string(version));
  DecodedState out;
  if (version >= 3) out.chain = r.get<std::uint64_t>();
  out.settings = read_state_settings(p, left);
  const std::uint32_t n_undo = r.get<std::uint32_t>(), n_redo = r.get<std::uint32_t>();
  if (std::uint64_t(n_undo) + n_redo > left / 16) byte_io::fail("truncated history");
  out.mesh = read_mesh_slots(p, left);
  out.history.set_limits(max_undo_steps, max_undo_bytes);
  out.history.read_history(out.mesh, p, left, n_undo, n_redo);
  if (left != 0) byte_io::fail(std::to_string(left) + " unexpected bytes at the end");
  return out;
}

}  // namespace adasculpt::sculpt
