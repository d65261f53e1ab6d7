// `adasculpt replay IN SESSION.json OUT [--json]`: runs a sculpting session file (see
// sculpt/session_file.h) on a mesh and writes the result; --json prints the replay report
// (frames, frame-time median/p95/max, per-phase medians, final counts and angles).
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "io/load_mesh.h"
#include "sculpt/session.h"
#include "sculpt/session_file.h"

namespace adasculpt::cli {

namespace {

struct ReplayOptions {
  std::string in, session, out;
  bool json = false;
  std::string field_solve = "carried";
  long long roi_max_vertices = -1;  // -1: the default budget
};

void run_replay(const ReplayOptions& o) {
  std::ifstream f(o.session, std::ios::binary);
  if (!f) throw std::invalid_argument(o.session + ": cannot open the session file");
  std::stringstream text;
  text << f.rdbuf();
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::parse_error& e) {
    throw std::invalid_argument(o.session + ": not valid JSON: " + e.what());
  }
  try {
    sculpt::parse_session_file(j);  // validate before the (possibly slow) mesh load
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(o.session + ": " + e.what());
  }
  io::format_from_path(o.out);  // an unknown output extension fails before the work

  std::vector<std::string> warnings;
  sculpt::Session session;
  deform::DeformOptions& grab = session.grab_options();
  grab.field_solve = o.field_solve == "every-frame" ? deform::FieldSolve::EveryFrame : deform::FieldSolve::Carried;
  if (o.roi_max_vertices >= 0) grab.max_roi_vertices = size_t(o.roi_max_vertices);
  session.load(load_input(o.in, warnings));
  print_warnings(warnings);
  const nlohmann::json report = session.replay(j);
  io::save_mesh(session.mesh(), o.out);
  if (o.json) {
    print_json(report);
    return;
  }
  std::printf("%s -> %s\n", o.in.c_str(), o.out.c_str());
  std::printf("  frames                     %d\n", report["frames"].get<int>());
  std::printf("  frame ms median/p95/max    %.3f / %.3f / %.3f\n", report["frame_ms_median"].get<double>(),
              report["frame_ms_p95"].get<double>(), report["frame_ms_max"].get<double>());
  std::printf("  median roi/field/refine/deform/remesh ms  %.3f / %.3f / %.3f / %.3f / %.3f\n",
              report["roi_ms_median"].get<double>(), report["field_ms_median"].get<double>(),
              report["refine_ms_median"].get<double>(), report["deform_ms_median"].get<double>(),
              report["remesh_ms_median"].get<double>());
  if (report["roi_capped"].get<bool>())
    std::printf("  ROI cut to the vertex budget (%zu vertices; --roi-max-vertices)\n", session.grab_options().max_roi_vertices);
  std::printf("  vertices / faces           %zu / %zu\n", report["vertices"].get<size_t>(),
              report["faces"].get<size_t>());
  std::printf("  min angle / mean min angle %.4f / %.4f deg\n", report["min_angle_deg"].get<double>(),
              report["mean_min_angle_deg"].get<double>());
}

}  // namespace

void register_replay(CLI::App& app) {
  auto options = std::make_shared<ReplayOptions>();
  CLI::App* cmd = app.add_subcommand("replay", "Run a sculpting session file on a mesh and write the result");
  cmd->add_option("IN", options->in, "input mesh (.off .obj .stl .ply)")->required();
  cmd->add_option("SESSION", options->session, "session file (JSON, version 1)")->required();
  cmd->add_option("OUT", options->out, "output mesh (format from the extension)")->required();
  cmd->add_flag("--json", options->json, "print the replay report as one JSON object");
  cmd->add_option("--field-solve", options->field_solve,
                  "grab field: carried (default; exact solves spread over frames) or every-frame (the paper)")
      ->check(CLI::IsMember({"carried", "every-frame"}));
  cmd->add_option("--roi-max-vertices", options->roi_max_vertices,
                  "vertex budget of a grab's region of interest (0 = none; default 20000)")
      ->check(CLI::NonNegativeNumber);
  cmd->callback([options] { run_replay(*options); });
}

}  // namespace adasculpt::cli
