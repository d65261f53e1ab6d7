#pragma once
// The quality report every remeshing result is judged by: element counts, topology,
// triangle angles (the paper's Table 1 figures), valence regularity, edge lengths, and the
// sampled distance to a reference surface.
#include <cstddef>
#include <map>

#include <nlohmann/json_fwd.hpp>

#include "mesh/surface_mesh.h"

namespace adasculpt::geometry {

struct QualityReport {
  size_t vertices = 0, faces = 0, edges = 0;
  int boundary_loops = 0, components = 0, genus = 0;
  // Angles in degrees. A zero-area triangle counts as 0 / 180 degrees.
  double min_angle_deg = 0, max_angle_deg = 0;
  double mean_min_angle_deg = 0;  // mean over triangles of their smallest angle ("Ave angle")
  double pct_min_angle_lt_30 = 0, pct_min_angle_lt_10 = 0;  // percent of triangles
  // Over interior (non-boundary, non-isolated) vertices.
  std::map<int, size_t> valence_histogram;
  double valence_6_pct = 0;
  double edge_length_min = 0, edge_length_mean = 0, edge_length_max = 0, edge_length_std = 0;
  // The same divided by bbox_diag (scale-free, comparable across meshes).
  double edge_length_min_rel = 0, edge_length_mean_rel = 0, edge_length_max_rel = 0, edge_length_std_rel = 0;
  size_t degenerate_faces = 0;  // area < 1e-12 * bbox_diag^2
  double bbox_diag = 0, area = 0;
};

QualityReport quality_report(const mesh::SurfaceMesh& mesh);

// One triangle's share of the angle figures: its smallest and largest angle in degrees (0 and 180
// for a zero-area triangle) and its area.
struct TriangleAngles {
  double min_deg = 0, max_deg = 0, area = 0;
};
TriangleAngles triangle_angle_extremes(const Point& a, const Point& b, const Point& c);

// Symmetric sampled distance between two surfaces: the max of both directions.
struct DistanceReport {
  double rms = 0, hausdorff = 0;
  double rms_rel = 0, hausdorff_rel = 0;  // divided by the reference's bounding-box diagonal
  // Where the Hausdorff distance is reached: a point of the mesh (hausdorff_on_reference false) or
  // of the reference, and the closest point to it on the other surface.
  Point hausdorff_at{0.0}, hausdorff_closest{0.0};
  bool hausdorff_on_reference = false;
};

// `samples` points per direction spread over the source surface in proportion to triangle
// area (deterministic: fixed seed), plus every vertex for the Hausdorff distance; each
// measured exactly against the other surface through a TriangleTree. RMS uses the area
// samples only. Throws std::invalid_argument if either mesh has no non-degenerate face.
DistanceReport distance_between(const mesh::SurfaceMesh& mesh, const mesh::SurfaceMesh& reference,
                                size_t samples = 200000);

// Keys: vertices, faces, edges, boundary_loops, components, genus, min_angle_deg,
// max_angle_deg, mean_min_angle_deg, pct_min_angle_lt_30, pct_min_angle_lt_10,
// valence_6_pct, valence_histogram ({"6": n, ...}), edge_length_min, edge_length_mean,
// edge_length_max, edge_length_std, edge_length_mean_rel, degenerate_faces, bbox_diag, area.
nlohmann::json to_json(const QualityReport& report);
nlohmann::json to_json(const DistanceReport& report);

}  // namespace adasculpt::geometry
