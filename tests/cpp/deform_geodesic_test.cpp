// Geodesic distance for the ROI: the triangle (fast-marching) update makes the ROI round on an
// irregular mesh, where plain Dijkstra on edges is biased.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <glm/geometric.hpp>

#include "deform/geodesic.h"
#include "mesh/primitives.h"

using namespace adasculpt;
using mesh::Vertex;

namespace {

// A flat grid with every vertex jittered in the plane: irregular, but geodesic = Euclidean.
mesh::SurfaceMesh irregular_plane(int n) {
  mesh::SurfaceMesh m = mesh::make_grid(n, 2.0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  const double h = 2.0 / n;
  for (Vertex v : m.vertices())
    if (!m.is_boundary(v)) {
      m.position(v).x += jitter(rng) * h;
      m.position(v).y += jitter(rng) * h;
    }
  return m;
}

Vertex nearest(const mesh::SurfaceMesh& m, const Point& p) {
  Vertex best;
  double bd = 1e300;
  for (Vertex v : m.vertices()) {
    const double d = glm::length(m.position(v) - p);
    if (d < bd) bd = d, best = v;
  }
  return best;
}

struct RoiShape {
  double ratio;      // max / min Euclidean radius of the ROI boundary
  double max_error;  // max |geodesic - euclidean| / radius inside the ROI
  size_t reached;
};

RoiShape measure(const mesh::SurfaceMesh& m, bool edges_only, double radius) {
  const Vertex s = nearest(m, Point(0.0));
  const Point c = m.position(s);
  deform::GeodesicWorkspace ws;
  deform::geodesic_distance(m, {{s, 0.0}}, radius, ws, edges_only);
  double rmin = 1e300, rmax = 0, err = 0;
  for (Vertex v : ws.order()) {
    const double e = glm::length(m.position(v) - c);
    err = std::max(err, std::abs(ws.distance(v) - e) / radius);
    bool border = false;
    for (Vertex u : m.vertices(v)) border = border || !ws.reached(u);
    if (border) rmin = std::min(rmin, e), rmax = std::max(rmax, e);
  }
  return {rmax / rmin, err, ws.order().size()};
}

}  // namespace

TEST(DeformGeodesic, TriangleUpdateIsExactForAPlanarFront) {
  // A point source S below AB: the update recovers |S - C| exactly.
  const Point a(0, 0, 0), b(1, 0, 0), c(0.5, 0.8, 0), s(0.3, -2.0, 0);
  EXPECT_NEAR(deform::triangle_update(a, b, c, glm::length(a - s), glm::length(b - s)), glm::length(c - s), 1e-12);
  // Edge fallback when the straight path from S to C misses AB.
  const Point s2(-1, -1, 0), c2(3, 0.1, 0);
  const double da = glm::length(a - s2), db = glm::length(b - s2);
  EXPECT_NEAR(deform::triangle_update(a, b, c2, da, db),
              std::min(da + glm::length(c2 - a), db + glm::length(c2 - b)), 1e-12);
}

TEST(DeformGeodesic, RoiIsRoundOnAnIrregularMesh) {
  const mesh::SurfaceMesh m = irregular_plane(80);
  const double radius = 0.6;
  const RoiShape fmm = measure(m, false, radius);
  const RoiShape dijkstra = measure(m, true, radius);
  RecordProperty("fmm_ratio", std::to_string(fmm.ratio));
  RecordProperty("dijkstra_ratio", std::to_string(dijkstra.ratio));
  std::printf("ROI roundness max/min: fast marching %.3f (error %.3f), Dijkstra %.3f (error %.3f)\n", fmm.ratio,
              fmm.max_error, dijkstra.ratio, dijkstra.max_error);
  EXPECT_LT(fmm.ratio, 1.12);
  EXPECT_LT(fmm.ratio, dijkstra.ratio);
  EXPECT_LT(fmm.max_error, 0.04);
  EXPECT_LT(fmm.max_error, 0.5 * dijkstra.max_error);
}

TEST(DeformGeodesic, WorkStaysInsideTheRadius) {
  const mesh::SurfaceMesh m = irregular_plane(80);
  const RoiShape small = measure(m, false, 0.1);
  // pi r^2 / (h^2 / 2 per vertex ... ) : about pi * 0.01 / (2/80)^2 = 50 vertices, never the mesh.
  EXPECT_LT(small.reached, 120u);
  EXPECT_GT(small.reached, 20u);
}
