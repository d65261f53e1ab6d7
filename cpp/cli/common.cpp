#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "io/load_mesh.h"

namespace adasculpt::cli {

mesh::SurfaceMesh load_input(const std::string& path, std::vector<std::string>& warnings) {
  return io::load_mesh(path, &warnings);
}

void print_warnings(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings) std::cerr << "adasculpt: warning: " << w << '\n';
}

void print_json(const nlohmann::json& object) {
  // Non-finite numbers become null rather than invalid JSON; replace invalid UTF-8 (e.g.
  // from a file name) instead of throwing halfway through the output.
  std::cout << object.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << '\n';
}

}  // namespace adasculpt::cli
