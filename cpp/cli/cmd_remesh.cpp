// `adasculpt remesh IN OUT [--epsilon E] [--min-length A] [--max-length B] | [--uniform] [--length L]
// [--iterations N] [--no-projection] [--features DEG] [--max-vertices N] [--json]`
// --length alone means uniform remeshing: a length that silently went unused (adaptive by default)
// left a user with a mesh at the default tolerance and no word why. The adaptive options with
// --uniform or --length are a usage error for the same reason.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "geometry/quality.h"
#include "io/load_mesh.h"
#include "remesh/length_spec.h"
#include "remesh/remesher.h"

namespace adasculpt::cli {

namespace {

struct RemeshArgs {
  std::string input, output;
  bool uniform = false;  // --uniform, or --length given
  std::string epsilon = remesh::percent_text(remesh::kDefaultEpsilonPct),
              min_length = remesh::percent_text(remesh::kDefaultMinLengthPct),
              max_length = remesh::percent_text(remesh::kDefaultMaxLengthPct),
              length = remesh::percent_text(remesh::kDefaultTargetLengthPct);
  int iterations = 5;
  bool no_projection = false;
  double features = 0;
  bool json = false;
  size_t samples = 100000;
  size_t max_vertices = remesh::RemeshOptions::kDefaultMaxVertices;
};

void run_remesh(const RemeshArgs& a) {
  std::vector<std::string> warnings;
  mesh::SurfaceMesh m = load_input(a.input, warnings);
  print_warnings(warnings);
  const double diagonal = remesh::bounding_box_diagonal(m);
  remesh::RemeshOptions o;
  o.adaptive = !a.uniform;
  o.epsilon = remesh::parse_length(a.epsilon, diagonal, "--epsilon");
  o.min_length = remesh::parse_length(a.min_length, diagonal, "--min-length");
  o.max_length = remesh::parse_length(a.max_length, diagonal, "--max-length");
  o.target_length = remesh::parse_length(a.length, diagonal, "--length");
  o.iterations = a.iterations;
  o.projection = !a.no_projection;
  o.feature_angle_deg = a.features;
  o.max_vertices = a.max_vertices;
  remesh::check_options(o);

  const mesh::SurfaceMesh input = m;
  auto start = std::chrono::steady_clock::now();
  const remesh::RemeshReport report = remesh::remesh(m, o);
  double remesh_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  io::save_mesh(m, a.output);
  if (!report.warning.empty()) print_warnings({report.warning});  // one line; the result is still written

  const geometry::QualityReport q = geometry::quality_report(m);
  if (!a.json) {
    std::printf("%s -> %s: %zu vertices, %zu faces in %.1f ms; min angle %.2f deg, mean min angle %.2f deg\n",
                a.input.c_str(), a.output.c_str(), q.vertices, q.faces, remesh_ms, q.min_angle_deg,
                q.mean_min_angle_deg);
    return;
  }
  const geometry::DistanceReport d = geometry::distance_between(m, input, a.samples);
  nlohmann::json out = geometry::to_json(q);
  out["remesh_ms"] = remesh_ms;
  out["rms_rel"] = d.rms_rel;
  out["hausdorff_rel"] = d.hausdorff_rel;
  out["epsilon"] = o.epsilon;
  out["epsilon_rel"] = o.epsilon / diagonal;
  out["input_vertices"] = input.n_vertices();
  out["input_faces"] = input.n_faces();
  out["estimated_vertices"] = report.estimated_vertices;
  out["vertex_budget"] = report.vertex_budget;
  if (!report.warning.empty()) out["warning"] = report.warning;
  print_json(out);
}

}  // namespace

void register_remesh(CLI::App& app) {
  auto a = std::make_shared<RemeshArgs>();
  CLI::App* cmd = app.add_subcommand(
      "remesh", "Remesh a mesh: curvature-adaptive (default) or uniform isotropic. Lengths are absolute or "
                "a percentage of the bounding-box diagonal with a % suffix.");
  cmd->add_option("IN", a->input, "input mesh (.off .obj .stl .ply)")->required();
  cmd->add_option("OUT", a->output, "output mesh; the format follows the extension")->required();
  CLI::Option* uniform =
      cmd->add_flag("--uniform", a->uniform, "uniform target length (--length) instead of the adaptive sizing field");
  CLI::Option* length =
      cmd->add_option("--length", a->length, "target edge length (uniform; implies --uniform)")->capture_default_str();
  for (CLI::Option* adaptive :
       {cmd->add_option("--epsilon", a->epsilon, "approximation tolerance (adaptive)")->capture_default_str(),
        cmd->add_option("--min-length", a->min_length, "smallest target edge length (adaptive)")->capture_default_str(),
        cmd->add_option("--max-length", a->max_length, "largest target edge length (adaptive)")->capture_default_str()})
    adaptive->excludes(uniform)->excludes(length);
  cmd->add_option("--iterations", a->iterations, "remeshing iterations")->capture_default_str();
  cmd->add_flag("--no-projection", a->no_projection, "do not project vertices back onto the input surface");
  cmd->add_option("--features", a->features, "keep edges sharper than this dihedral angle (degrees); 0 = off")
      ->capture_default_str();
  cmd->add_option("--max-vertices", a->max_vertices,
                  "hard limit on the output's vertices (refinement stops there with a warning)")
      ->capture_default_str();
  cmd->add_flag("--json", a->json, "print one JSON object with the figures (includes distance to the input)");
  cmd->callback([a, length] {
    if (length->count() > 0) a->uniform = true;
    run_remesh(*a);
  });
}

}  // namespace adasculpt::cli
