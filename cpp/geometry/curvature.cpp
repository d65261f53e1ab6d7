#include "geometry/curvature.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "geometry/portable_math.h"
#include "geometry/triangle.h"

namespace adasculpt::geometry {

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

// Calls fn(p, q, r) for every face around v, with p = position of v and p, q, r in the
// face's own (counter-clockwise) order.
template <class Fn>
void for_each_corner(const mesh::SurfaceMesh& mesh, mesh::Vertex v, Fn&& fn) {
  const Point& p = mesh.position(v);
  for (mesh::Halfedge h : mesh.halfedges(v)) {
    if (mesh.is_boundary(h)) continue;
    fn(p, mesh.position(mesh.to_vertex(h)), mesh.position(mesh.to_vertex(mesh.next(h))));
  }
}

}  // namespace

double mixed_voronoi_area(const mesh::SurfaceMesh& mesh, mesh::Vertex v) {
  double area = 0.0;
  for_each_corner(mesh, v, [&](const Point& p, const Point& q, const Point& r) {
    const Vec3 pq = q - p, pr = r - p, qr = r - q;
    const double dot_p = glm::dot(pq, pr), dot_q = -glm::dot(pq, qr), dot_r = glm::dot(pr, qr);
    const double tri_area = 0.5 * glm::length(glm::cross(pq, pr));
    if (dot_p < 0) {
      area += 0.5 * tri_area;
    } else if (dot_q < 0 || dot_r < 0) {
      area += 0.25 * tri_area;
    } else {
      // Voronoi part: (|pr|^2 cot q + |pq|^2 cot r) / 8.
      area += 0.125 * (glm::dot(pr, pr) * cotan(p - q, r - q) + glm::dot(pq, pq) * cotan(p - r, q - r));
    }
  });
  return area;
}

Vec3 cotan_laplacian(const mesh::SurfaceMesh& mesh, mesh::Vertex v) {
  // Per face (p, q, r): edge pq is weighted by the cotangent at r and edge pr by the one at
  // q; summing over the fan gives cot(alpha) + cot(beta) for every interior edge.
  Vec3 sum(0.0);
  for_each_corner(mesh, v, [&](const Point& p, const Point& q, const Point& r) {
    sum += cotan(p - r, q - r) * (q - p) + cotan(p - q, r - q) * (r - p);
  });
  return sum;
}

namespace {
// cot from the scaled cosine and sine of an angle, with the clamping of cotan().
double cot_scaled(double cos_scaled, double sin_scaled) {
  if (sin_scaled == 0.0 && cos_scaled == 0.0) return 0.0;
  if (std::abs(cos_scaled) >= kMaxCotan * sin_scaled) return cos_scaled > 0 ? kMaxCotan : -kMaxCotan;
  return cos_scaled / sin_scaled;
}

// The sum of angles in [0, pi], each given as a scaled cosine and sine, with ONE atan2 instead of
// one per angle (the atan2s were a third of a sculpting frame's curvature work): the angles are
// added as the arguments of complex numbers multiplied together. Each angle is at most pi, so the
// running argument wraps past 2 pi exactly when it goes from the lower half-plane [pi, 2 pi) to
// the upper one [0, pi); the wraps are counted. The product is rescaled each step (its modulus is
// the product of edge-length squares and would underflow around a high-valence vertex).
class AngleSum {
 public:
  void add(double cos_scaled, double sin_scaled) {
    const bool was_lower = lower_half();
    const double x = x_ * cos_scaled - y_ * sin_scaled;
    const double y = x_ * sin_scaled + y_ * cos_scaled;
    const double scale = std::max(std::abs(x), std::abs(y));
    if (!(scale > 0.0)) return;  // a zero-area, zero-length corner adds no angle
    x_ = x / scale;
    y_ = y / scale;
    if (was_lower && !lower_half()) ++turns_;
  }
  double radians() const {
    double arg = portable::atan2(y_, x_);  // (-pi, pi]
    if (arg < 0.0) arg += kTwoPi;
    return turns_ * kTwoPi + arg;
  }

 private:
  // The argument is in [pi, 2 pi): below the real axis, or on its negative side.
  bool lower_half() const { return y_ < 0.0 || (y_ == 0.0 && x_ < 0.0); }
  double x_ = 1.0, y_ = 0.0;
  int turns_ = 0;
};
}  // namespace

double max_abs_curvature(const mesh::SurfaceMesh& mesh, mesh::Vertex v) {
  if (mesh.is_boundary(v)) return 0.0;  // also true for isolated vertices
  // One walk around the fan gathers what mixed_voronoi_area, cotan_laplacian and the angle
  // sum compute separately (the remesher calls this for every vertex of a sculpting region
  // every frame): each corner's cross product serves the area, both cotangents and the angle.
  double area = 0.0;
  AngleSum angle_sum;
  Vec3 laplacian(0.0);
  bool degenerate = false;
  for_each_corner(mesh, v, [&](const Point& p, const Point& q, const Point& r) {
    const Vec3 pq = q - p, pr = r - p, qr = r - q;
    const double dot_p = glm::dot(pq, pr), dot_q = -glm::dot(pq, qr), dot_r = glm::dot(pr, qr);
    const double twice_area = glm::length(glm::cross(pq, pr));
    const double pq2 = glm::dot(pq, pq), pr2 = glm::dot(pr, pr);
    degenerate = degenerate || is_degenerate_triangle(twice_area, pq2, pr2, glm::dot(qr, qr));
    const double cot_q = cot_scaled(dot_q, twice_area), cot_r = cot_scaled(dot_r, twice_area);
    laplacian += cot_r * pq + cot_q * pr;
    angle_sum.add(dot_p, twice_area);
    if (dot_p < 0)
      area += 0.25 * twice_area;
    else if (dot_q < 0 || dot_r < 0)
      area += 0.125 * twice_area;
    else
      area += 0.125 * (pr2 * cot_q + pq2 * cot_r);
  });
  // A zero-area triangle (collinear corners, as in CAD exports and CGAL's degtri_*.off) has no
  // normal and infinite cotangents: clamped to kMaxCotan, they gave a flat fan a large mean
  // curvature and the sizing field min_length there (degtri_sliding.off, flat, asked for 2,033
  // vertices at eps 0.5% instead of about 90). Like a boundary vertex it gets none; the
  // gradation limit lets its neighbours' sizing reach it.
  if (degenerate || !(area > 0.0)) return 0.0;
  const double mean = glm::length(laplacian) / (4.0 * area);
  // An angle defect within round-off of zero is zero: sqrt(H^2 - K) would otherwise turn
  // a 1e-15 defect on a flat patch into a 1e-7 curvature.
  double defect = kTwoPi - angle_sum.radians();
  if (std::abs(defect) < 1e-12) defect = 0.0;
  const double gauss = defect / area;
  return mean + std::sqrt(std::max(mean * mean - gauss, 0.0));
}

void max_abs_curvature(const mesh::SurfaceMesh& mesh, std::vector<double>& out) {
  out.assign(mesh.vertices_size(), 0.0);
  for (mesh::Vertex v : mesh.vertices()) out[v.idx] = max_abs_curvature(mesh, v);
}

}  // namespace adasculpt::geometry
