// distance_between (declared in quality.h): sampled RMS and Hausdorff distance between two
// surfaces, the fidelity figures of the quality report.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "geometry/aabb_tree.h"
#include "geometry/quality.h"
#include "geometry/topology.h"

namespace adasculpt::geometry {

namespace {

struct OneWay {
  double rms = 0, hausdorff = 0;
  Point at{0.0}, closest{0.0};  // where the largest distance is reached, and its closest point
};

// A double in [0, 1) from 53 random bits: std::uniform_real_distribution is
// implementation-defined, and the native and wasm builds must draw the same samples.
double unit_random(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// Distances from `source`'s surface to `target`: `samples` area samples (systematic
// allocation: triangle i gets floor(N*C_i/A) - floor(N*C_{i-1}/A) where C is the running
// area, so counts follow area exactly without randomness in the allocation), then every vertex.
OneWay one_way(const TriangleTree& source, const TriangleTree& target, size_t samples) {
  std::mt19937_64 rng(20130501);  // fixed: the same meshes always give the same figures
  const auto& pts = source.points();
  const auto& tris = source.triangles();
  double total = 0;
  for (const auto& t : tris) total += 0.5 * glm::length(glm::cross(pts[t[1]] - pts[t[0]], pts[t[2]] - pts[t[0]]));
  OneWay out;
  double sum2 = 0, running = 0;
  size_t taken = 0;
  TriangleTree::ClosestHit hint;
  // The largest squared distance so far (squared until the end), where and to what.
  auto note_farthest = [&](const Point& p) {
    if (!(hint.distance2 > out.hausdorff)) return;
    out.hausdorff = hint.distance2;
    out.at = p;
    out.closest = hint.point;
  };
  for (const auto& t : tris) {
    const Point &a = pts[t[0]], &b = pts[t[1]], &c = pts[t[2]];
    running += 0.5 * glm::length(glm::cross(b - a, c - a));
    const size_t until = std::min(samples, static_cast<size_t>(std::floor(samples * (running / total))));
    for (; taken < until; ++taken) {
      // sqrt warps the first variable so the points are uniform over the triangle's area.
      const double s = std::sqrt(unit_random(rng)), r = unit_random(rng);
      const Point p = (1 - s) * a + (s * (1 - r)) * b + (s * r) * c;
      hint = target.closest_point(p, hint);
      sum2 += hint.distance2;
      note_farthest(p);
    }
  }
  out.rms = taken > 0 ? std::sqrt(sum2 / taken) : 0.0;
  // Vertices: the points where two meshes differ most (corners cut by a remesher).
  std::vector<std::uint8_t> used(pts.size(), 0);
  for (const auto& t : tris) used[t[0]] = used[t[1]] = used[t[2]] = 1;
  for (size_t i = 0; i < pts.size(); ++i) {
    if (!used[i]) continue;
    hint = target.closest_point(pts[i], hint);
    note_farthest(pts[i]);
  }
  out.hausdorff = std::sqrt(out.hausdorff);
  return out;
}

}  // namespace

DistanceReport distance_between(const mesh::SurfaceMesh& mesh, const mesh::SurfaceMesh& reference, size_t samples) {
  TriangleTree a, b;
  a.build(mesh);
  b.build(reference);
  if (a.empty() || b.empty())
    throw std::invalid_argument(std::string(a.empty() ? "mesh" : "reference") + " has no non-degenerate triangle");
  const OneWay ab = one_way(a, b, samples), ba = one_way(b, a, samples);
  DistanceReport d;
  d.rms = std::max(ab.rms, ba.rms);
  d.hausdorff = std::max(ab.hausdorff, ba.hausdorff);
  d.hausdorff_on_reference = ba.hausdorff > ab.hausdorff;
  d.hausdorff_at = d.hausdorff_on_reference ? ba.at : ab.at;
  d.hausdorff_closest = d.hausdorff_on_reference ? ba.closest : ab.closest;
  const double diag = bounding_box_diagonal(reference);
  if (diag > 0) {
    d.rms_rel = d.rms / diag;
    d.hausdorff_rel = d.hausdorff / diag;
  }
  return d;
}

}  // namespace adasculpt::geometry
