// `adasculpt stats MESH [--reference REF [--features DEG]] [--json] [--samples N] [--self-intersections [--si-cap N]]`:
// the quality report of a mesh, with a reference its distance to it, and on request the
// number of self-intersecting face pairs.
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "geometry/quality.h"
#include "geometry/inherited_crossings.h"
#include "geometry/self_intersections.h"
#include "remesh/feature_sectors.h"

namespace adasculpt::cli {

namespace {

struct StatsOptions {
  std::string mesh;
  std::string reference;
  bool json = false;
  size_t samples = 200000;
  bool self_intersections = false;
  size_t si_cap = 100000;  // a badly broken mesh can have millions of pairs
  // With a reference: the smallest angle its feature lines (at this feature angle, as `remesh
  // --features` marks them; 0 = its boundary only) force on a remesh that keeps them.
  std::optional<double> features;
};

void print_table(const std::string& path, const geometry::QualityReport& r,
                 const std::optional<geometry::DistanceReport>& d, const std::string& reference,
                 const std::optional<geometry::SelfIntersectionReport>& si) {
  std::printf("%s\n", path.c_str());
  std::printf("  vertices / faces / edges   %zu / %zu / %zu\n", r.vertices, r.faces, r.edges);
  std::printf("  components                 %d\n", r.components);
  std::printf("  boundary loops             %d\n", r.boundary_loops);
  std::printf("  genus                      %d\n", r.genus);
  std::printf("  min / max angle            %.4f / %.4f deg\n", r.min_angle_deg, r.max_angle_deg);
  std::printf("  mean min angle (Ave)       %.4f deg\n", r.mean_min_angle_deg);
  std::printf("  min angle < 30 / < 10      %.2f %% / %.2f %%\n", r.pct_min_angle_lt_30, r.pct_min_angle_lt_10);
  std::printf("  valence 6 (interior)       %.2f %%\n", r.valence_6_pct);
  std::printf("  valence histogram         ");
  for (const auto& [valence, count] : r.valence_histogram) std::printf(" %d:%zu", valence, count);
  std::printf("\n");
  std::printf("  edge length min/mean/max   %.6g / %.6g / %.6g (std %.6g)\n", r.edge_length_min, r.edge_length_mean,
              r.edge_length_max, r.edge_length_std);
  std::printf("    relative to diagonal     %.6f / %.6f / %.6f\n", r.edge_length_min_rel, r.edge_length_mean_rel,
              r.edge_length_max_rel);
  std::printf("  degenerate faces           %zu\n", r.degenerate_faces);
  std::printf("  bounding box diagonal      %.6g\n", r.bbox_diag);
  std::printf("  area                       %.6g\n", r.area);
  if (si) {
    std::printf("  self-intersecting pairs    %zu%s (collinear faces left out: %zu)\n", si->pairs.size(),
                si->capped ? " (capped)" : "", si->degenerate_faces);
  }
  if (d) {
    std::printf("  distance to %s\n", reference.c_str());
    std::printf("    rms                      %.6g (%.3e of diagonal)\n", d->rms, d->rms_rel);
    std::printf("    hausdorff                %.6g (%.3e of diagonal)\n", d->hausdorff, d->hausdorff_rel);
    std::printf("      reached at             (%.6g, %.6g, %.6g) on the %s, closest (%.6g, %.6g, %.6g)\n",
                d->hausdorff_at.x, d->hausdorff_at.y, d->hausdorff_at.z, d->hausdorff_on_reference ? "reference" : "mesh",
                d->hausdorff_closest.x, d->hausdorff_closest.y, d->hausdorff_closest.z);
  }
}

void run_stats(const StatsOptions& o) {
  if (o.samples == 0) throw std::invalid_argument("--samples must be at least 1");
  std::vector<std::string> warnings;
  const mesh::SurfaceMesh m = load_input(o.mesh, warnings);
  std::optional<mesh::SurfaceMesh> reference;
  if (!o.reference.empty()) reference = load_input(o.reference, warnings);
  // Only now that every input loaded: an error must stay the single line on stderr.
  print_warnings(warnings);

  const geometry::QualityReport report = geometry::quality_report(m);
  std::optional<geometry::DistanceReport> distance;
  if (reference) distance = geometry::distance_between(m, *reference, o.samples);
  std::optional<geometry::SelfIntersectionReport> si;
  if (o.self_intersections) si = geometry::self_intersections(m, o.si_cap);
  // With a reference: how many of the crossings the reference did not already have there (a remesh
  // re-samples an input's own crossing into several pairs; see geometry/inherited_crossings.h). The
  // margin is twice the sampled Hausdorff distance: sampling can only under-estimate it.
  std::optional<size_t> reference_pairs, not_inherited;
  std::vector<size_t> new_pairs;  // positions in si->pairs of the pairs not inherited
  if (si && distance) {
    const geometry::SelfIntersectionReport ref_si = geometry::self_intersections(*reference, o.si_cap);
    reference_pairs = ref_si.pairs.size();
    not_inherited = geometry::count_crossings_not_inherited(m, *si, *reference, ref_si, 2.0 * distance->hausdorff,
                                                            &new_pairs);
  }

  std::optional<remesh::FeatureSector> sector;
  if (o.features)  // (CLI11 checks it comes with --reference and its range)
    sector = remesh::smallest_feature_sector(*reference, remesh::feature_edge_marks(*reference, *o.features));

  if (!o.json) {
    print_table(o.mesh, report, distance, o.reference, si);
    if (sector) {
      std::printf("  smallest feature sector of the reference   %.4f deg", sector->angle_deg);
      if (sector->vertex.is_valid()) {
        const Point& at = reference->position(sector->vertex);
        std::printf(" at (%.6g, %.6g, %.6g)", at.x, at.y, at.z);
      }
      std::printf("\n");
    }
    if (not_inherited)
      std::printf("  pairs not at the reference's own crossings   %zu (the reference has %zu pairs)\n", *not_inherited,
                  *reference_pairs);
    return;
  }
  nlohmann::json out = geometry::to_json(report);
  if (distance) {
    out["rms"] = distance->rms;
    out["hausdorff"] = distance->hausdorff;
    out["rms_rel"] = distance->rms_rel;
    out["hausdorff_rel"] = distance->hausdorff_rel;
    const Point& at = distance->hausdorff_at;
    out["hausdorff_at"] = {at.x, at.y, at.z};
    out["hausdorff_on_reference"] = distance->hausdorff_on_reference;
    out["samples"] = o.samples;
  }
  if (sector) out["reference_feature_sector_deg"] = sector->angle_deg;
  if (si) {
    out["self_intersecting_pairs"] = si->pairs.size();
    out["self_intersections_capped"] = si->capped;
    out["collinear_faces"] = si->degenerate_faces;
    if (not_inherited) {
      out["reference_self_intersecting_pairs"] = *reference_pairs;
      out["self_intersecting_pairs_not_inherited"] = *not_inherited;
    }
    // Where to look: the centroids of the first few crossing pairs' faces (with a reference, the
    // pairs not at its own crossings).
    std::vector<size_t> shown;
    if (!not_inherited)
      for (size_t i = 0; i < si->pairs.size() && i < 10; ++i) shown.push_back(i);
    else
      shown = new_pairs;
    nlohmann::json examples = nlohmann::json::array();
    for (size_t k = 0; k < shown.size() && k < 10; ++k) {
      const size_t i = shown[k];
      nlohmann::json pair = nlohmann::json::array();
      for (std::uint32_t f : {si->pairs[i].first, si->pairs[i].second}) {
        mesh::Vertex v[3];
        m.face_vertices(mesh::Face(f), v);
        const Point c = (m.position(v[0]) + m.position(v[1]) + m.position(v[2])) / 3.0;
        pair.push_back({{"face", f}, {"centroid", {c.x, c.y, c.z}}});
      }
      examples.push_back(pair);
    }
    out["self_intersection_examples"] = examples;
  }
  print_json(out);
}

}  // namespace

void register_stats(CLI::App& app) {
  auto options = std::make_shared<StatsOptions>();
  CLI::App* cmd = app.add_subcommand("stats", "Print the quality report of a mesh (and its distance to a reference)");
  cmd->add_option("MESH", options->mesh, "mesh file (.off .obj .stl .ply)")->required();
  CLI::Option* reference =
      cmd->add_option("--reference", options->reference, "reference mesh: adds RMS and Hausdorff distance");
  cmd->add_flag("--json", options->json, "print one JSON object instead of the table");
  cmd->add_option("--samples", options->samples, "area samples per direction for the distance")
      ->capture_default_str();
  cmd->add_flag("--self-intersections", options->self_intersections,
                "count self-intersecting face pairs (exact; same definition as CGAL's self_intersections)");
  cmd->add_option("--si-cap", options->si_cap, "stop counting self-intersecting pairs at this many")
      ->capture_default_str();
  cmd->add_option("--features", options->features,
                  "with --reference: the smallest angle between two feature edges meeting at a vertex of the "
                  "reference, marked as `remesh --features DEG` marks them (0: boundary edges only); a remesh that "
                  "keeps the features cannot have a larger minimum angle there")
      ->check(CLI::Range(0.0, 179.999))
      ->needs(reference);
  cmd->callback([options] { run_stats(*options); });
}

}  // namespace adasculpt::cli
