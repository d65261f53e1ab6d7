#pragma once
// The fuzzed entry points, shared by the libFuzzer targets (tests/fuzz/fuzz_target.cpp) and the
// GoogleTest that replays every saved input (tests/cpp/reliability_fuzz_regressions_test.cpp), so a
// crash found by the fuzzer is reproduced by ctest through exactly the same code.
//
// Contract checked for every input: the call either succeeds and its result honours the
// documented guarantees (readers: indices in range, finite coordinates; load_mesh: a mesh that
// passes validate() and survives an export/re-import round trip; session files: a parse that
// survives to_json() -> parse again, brush steps bit for bit and valid for Session::brush_stroke),
// or it refuses with the one documented exception type
// (io::IoError for files, std::invalid_argument for session files). Anything else — another
// exception type, a broken guarantee (ContractViolation), a sanitizer report — is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "deform/brushes.h"
#include "io/load_mesh.h"
#include "io/mesh_io.h"
#include "sculpt/session_file.h"

namespace adasculpt::fuzz {

// A documented guarantee does not hold for this input.
class ContractViolation : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

enum class Outcome { Accepted, Refused };

// Targets by name, the names of the corpus / regression folders and of the fuzzer binaries.
inline const std::vector<std::string>& target_names() {
  static const std::vector<std::string> names = {"off", "obj", "stl", "ply", "load_mesh", "session_file"};
  return names;
}

inline void check_soup(const io::PolygonSoup& soup) {
  for (const auto& p : soup.points)
    for (double c : p)
      if (!std::isfinite(c)) throw ContractViolation("reader returned a non-finite coordinate");
  for (const auto& t : soup.triangles)
    for (uint32_t i : t)
      if (i >= soup.points.size())
        throw ContractViolation("reader returned vertex index " + std::to_string(i) + " of " +
                                std::to_string(soup.points.size()));
}

inline Outcome run_reader(io::Format format, const uint8_t* data, size_t size) {
  io::PolygonSoup soup;
  try {
    soup = io::read_soup_from_memory(data, size, format, "fuzz");
  } catch (const io::IoError&) {
    return Outcome::Refused;
  }
  check_soup(soup);
  return Outcome::Accepted;
}

inline void check_mesh(const mesh::SurfaceMesh& m, const char* what) {
  try {
    m.validate();
  } catch (const std::exception& e) {
    throw ContractViolation(std::string(what) + ": " + e.what());
  }
  for (mesh::Vertex v : m.vertices()) {
    const Point& p = m.position(v);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw ContractViolation(std::string(what) + ": non-finite position");
  }
}

// The name hint has no known extension, so the format is sniffed from the content as for a
// dropped file without a name.
inline Outcome run_load_mesh(const uint8_t* data, size_t size) {
  mesh::SurfaceMesh m;
  std::vector<std::string> warnings;
  try {
    m = io::load_mesh_from_memory(data, size, "fuzz", &warnings);
  } catch (const io::IoError&) {
    return Outcome::Refused;
  }
  check_mesh(m, "loaded mesh");
  if (m.n_faces() == 0) throw ContractViolation("loaded a mesh without faces");
  // Whatever loads must export and load back to the same counts (no lost work on save).
  const std::vector<uint8_t> bytes = io::save_mesh_to_memory(m, io::Format::OFF);
  mesh::SurfaceMesh back;
  try {
    back = io::load_mesh_from_memory(bytes.data(), bytes.size(), "roundtrip.off");
  } catch (const io::IoError& e) {
    throw ContractViolation(std::string("exported mesh does not load back: ") + e.what());
  }
  check_mesh(back, "re-imported mesh");
  if (back.n_vertices() != m.n_vertices() || back.n_faces() != m.n_faces())
    throw ContractViolation("export/import changed the counts: " + std::to_string(m.n_vertices()) + "/" +
                            std::to_string(m.n_faces()) + " -> " + std::to_string(back.n_vertices()) + "/" +
                            std::to_string(back.n_faces()));
  return Outcome::Accepted;
}

// A parsed brush step is one Session::brush_stroke accepts: valid settings (check_brush_settings
// does not throw), a non-empty path of finite points, one pressure in [0, 1] per point or none.
inline void check_brush(const sculpt::BrushStroke& b) {
  try {
    deform::check_brush_settings(b.settings);
  } catch (const std::exception& e) {
    throw ContractViolation(std::string("parsed brush settings are refused by the brush: ") + e.what());
  }
  if (b.path.empty()) throw ContractViolation("brush step without a path");
  for (const Point& p : b.path)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw ContractViolation("brush path point is not finite");
  if (!b.pressure.empty() && b.pressure.size() != b.path.size())
    throw ContractViolation("brush pressure count differs from the path's");
  for (double x : b.pressure)
    if (!(x >= 0 && x <= 1)) throw ContractViolation("brush pressure outside [0, 1]");
}

// Bit-for-bit the same stroke (what a saved session must replay exactly).
inline bool same_stroke(const sculpt::BrushStroke& a, const sculpt::BrushStroke& b) {
  const deform::BrushSettings &x = a.settings, &y = b.settings;
  if (x.tool != y.tool || x.radius != y.radius || x.strength != y.strength || x.spacing != y.spacing ||
      x.invert != y.invert || x.symmetry_axis != y.symmetry_axis)
    return false;
  if (a.path.size() != b.path.size() || a.pressure != b.pressure) return false;
  for (size_t i = 0; i < a.path.size(); ++i)
    if (a.path[i] != b.path[i]) return false;
  return true;
}

// Bit-for-bit the same mask operation.
inline bool same_mask_op(const sculpt::MaskOp& a, const sculpt::MaskOp& b) {
  return a.kind == b.kind && a.path == b.path && a.radius == b.radius && a.strength == b.strength;
}

inline Outcome run_session_file(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  sculpt::SessionFile f;
  try {
    f = sculpt::parse_session_file(text);
  } catch (const std::invalid_argument&) {
    return Outcome::Refused;
  }
  for (const sculpt::SessionStep& s : f.steps) {
    if (s.count < 1) throw ContractViolation("step count below 1");
    if (s.kind == sculpt::SessionStep::Kind::Brush) check_brush(s.brush);
    if (s.kind == sculpt::SessionStep::Kind::Mask) {
      try {
        sculpt::check_mask_op(s.mask);  // what the Session checks again before it runs one
      } catch (const std::invalid_argument& e) {
        throw ContractViolation(std::string("a parsed mask step fails its check: ") + e.what());
      }
    }
    if (s.kind != sculpt::SessionStep::Kind::Grab) continue;
    if (s.grab.substeps < 1) throw ContractViolation("grab with substeps below 1");
    for (double t : {0.0, 0.5, 1.0}) {
      const deform::HandleTransform h = s.grab.total_at(t);
      const double vals[] = {h.translation.x, h.translation.y, h.translation.z, h.rotation.w, h.rotation.x,
                             h.rotation.y,    h.rotation.z,    h.scale};
      for (double v : vals)
        if (!std::isfinite(v)) throw ContractViolation("grab transform is not finite");
    }
  }
  // What we write we must read back (session files are saved by the browser and replayed).
  const std::string again = sculpt::to_json(f).dump();
  sculpt::SessionFile g;
  try {
    g = sculpt::parse_session_file(again);
  } catch (const std::invalid_argument& e) {
    throw ContractViolation(std::string("to_json output does not parse back: ") + e.what() + "\n" + again);
  }
  if (g.steps.size() != f.steps.size()) throw ContractViolation("to_json round trip changed the step count");
  for (size_t i = 0; i < f.steps.size(); ++i) {
    if (g.steps[i].kind != f.steps[i].kind) throw ContractViolation("to_json round trip changed a step's kind");
    if (f.steps[i].kind == sculpt::SessionStep::Kind::Brush && !same_stroke(f.steps[i].brush, g.steps[i].brush))
      throw ContractViolation("to_json round trip changed brush step " + std::to_string(i + 1) + "\n" + again);
    if (f.steps[i].kind == sculpt::SessionStep::Kind::Mask && !same_mask_op(f.steps[i].mask, g.steps[i].mask))
      throw ContractViolation("to_json round trip changed mask step " + std::to_string(i + 1) + "\n" + again);
  }
  return Outcome::Accepted;
}

// Throws std::invalid_argument for an unknown target name.
inline Outcome run_target(const std::string& target, const uint8_t* data, size_t size) {
  if (target == "off") return run_reader(io::Format::OFF, data, size);
  if (target == "obj") return run_reader(io::Format::OBJ, data, size);
  if (target == "stl") return run_reader(io::Format::STL, data, size);
  if (target == "ply") return run_reader(io::Format::PLY, data, size);
  if (target == "load_mesh") return run_load_mesh(data, size);
  if (target == "session_file") return run_session_file(data, size);
  throw std::invalid_argument("unknown fuzz target '" + target + "'");
}

}  // namespace adasculpt::fuzz
