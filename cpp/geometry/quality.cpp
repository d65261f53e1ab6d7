#include "geometry/quality.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "geometry/topology.h"
#include "geometry/triangle.h"

namespace adasculpt::geometry {

namespace {

constexpr double kRadToDeg = 57.295779513082320876798154814105;

void angle_figures(const mesh::SurfaceMesh& mesh, QualityReport& r) {
  const double degenerate_area = 1e-12 * r.bbox_diag * r.bbox_diag;
  double sum_min = 0, lo = std::numeric_limits<double>::infinity(), hi = -lo;
  size_t lt30 = 0, lt10 = 0;
  for (mesh::Face f : mesh.faces()) {
    mesh::Vertex v[3];
    mesh.face_vertices(f, v);
    const TriangleAngles t = triangle_angle_extremes(mesh.position(v[0]), mesh.position(v[1]), mesh.position(v[2]));
    const double area = t.area, amin = t.min_deg, amax = t.max_deg;
    r.area += area;
    if (area < degenerate_area) ++r.degenerate_faces;
    sum_min += amin;
    lo = std::min(lo, amin);
    hi = std::max(hi, amax);
    lt30 += amin < 30;
    lt10 += amin < 10;
  }
  if (r.faces == 0) return;
  r.min_angle_deg = lo;
  r.max_angle_deg = hi;
  r.mean_min_angle_deg = sum_min / r.faces;
  r.pct_min_angle_lt_30 = 100.0 * lt30 / r.faces;
  r.pct_min_angle_lt_10 = 100.0 * lt10 / r.faces;
}

void valence_figures(const mesh::SurfaceMesh& mesh, QualityReport& r) {
  size_t interior = 0;
  for (mesh::Vertex v : mesh.vertices()) {
    if (mesh.is_boundary(v)) continue;  // also skips isolated vertices
    ++interior;
    ++r.valence_histogram[static_cast<int>(mesh.valence(v))];
  }
  if (interior > 0) {
    auto it = r.valence_histogram.find(6);
    r.valence_6_pct = 100.0 * (it == r.valence_histogram.end() ? 0 : it->second) / interior;
  }
}

void edge_figures(const mesh::SurfaceMesh& mesh, QualityReport& r) {
  double sum = 0, sum2 = 0, lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (mesh::Edge e : mesh.edges()) {
    const double len = glm::length(mesh.position(mesh.vertex(e, 1)) - mesh.position(mesh.vertex(e, 0)));
    sum += len;
    sum2 += len * len;
    lo = std::min(lo, len);
    hi = std::max(hi, len);
  }
  if (r.edges == 0) return;
  r.edge_length_min = lo;
  r.edge_length_max = hi;
  r.edge_length_mean = sum / r.edges;
  r.edge_length_std = std::sqrt(std::max(sum2 / r.edges - r.edge_length_mean * r.edge_length_mean, 0.0));
  if (r.bbox_diag > 0) {
    r.edge_length_min_rel = r.edge_length_min / r.bbox_diag;
    r.edge_length_mean_rel = r.edge_length_mean / r.bbox_diag;
    r.edge_length_max_rel = r.edge_length_max / r.bbox_diag;
    r.edge_length_std_rel = r.edge_length_std / r.bbox_diag;
  }
}

}  // namespace

TriangleAngles triangle_angle_extremes(const Point& a, const Point& b, const Point& c) {
  TriangleAngles t;
  t.area = 0.5 * glm::length(glm::cross(b - a, c - a));
  if (t.area == 0) {  // coincident corners have no meaningful angles
    t.min_deg = 0;
    t.max_deg = 180;
    return t;
  }
  double ang[3];
  triangle_angles(a, b, c, ang);
  t.min_deg = std::min({ang[0], ang[1], ang[2]}) * kRadToDeg;
  t.max_deg = std::max({ang[0], ang[1], ang[2]}) * kRadToDeg;
  return t;
}

QualityReport quality_report(const mesh::SurfaceMesh& mesh) {
  QualityReport r;
  r.vertices = mesh.n_vertices();
  r.faces = mesh.n_faces();
  r.edges = mesh.n_edges();
  r.boundary_loops = geometry::boundary_loops(mesh);
  r.components = geometry::components(mesh);
  r.genus = geometry::genus(mesh);
  r.bbox_diag = bounding_box_diagonal(mesh);
  angle_figures(mesh, r);
  valence_figures(mesh, r);
  edge_figures(mesh, r);
  return r;
}

nlohmann::json to_json(const QualityReport& r) {
  nlohmann::json histogram = nlohmann::json::object();
  for (const auto& [valence, count] : r.valence_histogram) histogram[std::to_string(valence)] = count;
  return {
      {"vertices", r.vertices},
      {"faces", r.faces},
      {"edges", r.edges},
      {"boundary_loops", r.boundary_loops},
      {"components", r.components},
      {"genus", r.genus},
      {"min_angle_deg", r.min_angle_deg},
      {"max_angle_deg", r.max_angle_deg},
      {"mean_min_angle_deg", r.mean_min_angle_deg},
      {"pct_min_angle_lt_30", r.pct_min_angle_lt_30},
      {"pct_min_angle_lt_10", r.pct_min_angle_lt_10},
      {"valence_6_pct", r.valence_6_pct},
      {"valence_histogram", histogram},
      {"edge_length_min", r.edge_length_min},
      {"edge_length_mean", r.edge_length_mean},
      {"edge_length_max", r.edge_length_max},
      {"edge_length_std", r.edge_length_std},
      {"edge_length_mean_rel", r.edge_length_mean_rel},
      {"degenerate_faces", r.degenerate_faces},
      {"bbox_diag", r.bbox_diag},
      {"area", r.area},
  };
}

nlohmann::json to_json(const DistanceReport& d) {
  return {{"rms", d.rms}, {"hausdorff", d.hausdorff}, {"rms_rel", d.rms_rel}, {"hausdorff_rel", d.hausdorff_rel}};
}

}  // namespace adasculpt::geometry
