// adasculpt: the native command-line tool. This file only sets up CLI11 and turns every
// failure into the one-line error contract described in commands.h.
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/commands.h"

#ifndef ADASCULPT_VERSION
#define ADASCULPT_VERSION "unknown"
#endif

// The subcommands, in --help order. Adding one: cmd_<name>.cpp plus one X(<name>) here.
#define ADASCULPT_COMMANDS(X) X(stats) X(remesh) X(replay)

namespace adasculpt::cli {
#define ADASCULPT_DECLARE(name) void register_##name(CLI::App& app);
ADASCULPT_COMMANDS(ADASCULPT_DECLARE)
#undef ADASCULPT_DECLARE
}  // namespace adasculpt::cli

namespace {

// Error messages may quote file content; the contract is one line, so fold newlines.
std::string one_line(std::string message) {
  for (char& c : message)
    if (c == '\n' || c == '\r') c = ' ';
  return message;
}

int fail(const std::string& message) {
  std::cout.flush();
  std::cerr << "adasculpt: error: " << one_line(message) << std::endl;
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"adasculpt: curvature-adaptive remeshing and sculpting (Dunyach et al. 2013)", "adasculpt"};
  app.set_version_flag("--version", "adasculpt " ADASCULPT_VERSION);
  app.require_subcommand(1);
#define ADASCULPT_REGISTER(name) adasculpt::cli::register_##name(app);
  ADASCULPT_COMMANDS(ADASCULPT_REGISTER)
#undef ADASCULPT_REGISTER
  try {
    app.parse(argc, argv);  // subcommand callbacks run inside
  } catch (const CLI::Success& e) {
    return app.exit(e);  // --help, --version: printed on stdout, exit 0
  } catch (const CLI::Error& e) {
    return fail(std::string(e.what()) + " (see adasculpt --help)");
  } catch (const std::exception& e) {
    return fail(e.what());
  } catch (...) {
    return fail("unexpected failure");
  }
  std::cout.flush();
  if (!std::cout) return fail("cannot write to standard output");
  return 0;
}
