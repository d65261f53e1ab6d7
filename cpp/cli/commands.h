#pragma once
// What the subcommands of the `adasculpt` tool share. A subcommand lives in its own file
// cmd_<name>.cpp defining `void register_<name>(CLI::App& app)` in adasculpt::cli, which
// adds a CLI11 subcommand whose callback does the work; then add one line `X(<name>)` to
// ADASCULPT_COMMANDS in main.cpp.
//
// The exit-code contract (kept by main.cpp): 0 on success; 2 with exactly one line
// "adasculpt: error: <message>" on stderr for bad usage or input. A callback reports
// failure by throwing (any std::exception); it never prints the error itself.
// stdout carries only results, so `--json` output can be piped; warnings go to stderr.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json_fwd.hpp>

#include "mesh/surface_mesh.h"

namespace adasculpt::cli {

// Loads a mesh file; repair warnings are appended to *warnings (not printed: if a later
// input fails, the error must be the only line on stderr).
mesh::SurfaceMesh load_input(const std::string& path, std::vector<std::string>& warnings);
// "adasculpt: warning: <w>" on stderr, one line each.
void print_warnings(const std::vector<std::string>& warnings);
// One JSON object on one line of stdout.
void print_json(const nlohmann::json& object);

}  // namespace adasculpt::cli
