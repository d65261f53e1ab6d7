#pragma once
// The fuzzed entry points, shared by the libFuzzer targets (tests/fuzz/fuzz_target.cpp) and the
// GoogleTest that replays every saved input (tests/cpp/reliability_fuzz_regressions_test.cpp), so a
// crash found by the fuzzer is reproduced by ctest through exactly the same code.
//
// Contract checked for every input: the call either succeeds and its result honours the
// documented guarantees (readers: indices in range, finite coordinates; load_mesh: a mesh that
// passes validate() and survives an export/re-import round trip; session files: a parse that
// survives to_json() -> parse again), or it refuses with the one documented exception type
// (io::IoError for files, std::invalid_argument for session files). Anything else — another
// exception type, a broken guarantee (ContractViolation), a sanitizer report — is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

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
