#include "geometry/triangle.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "geometry/portable_math.h"

namespace adasculpt::geometry {

namespace {

void corners(const mesh::SurfaceMesh& mesh, mesh::Face f, Point out[3]) {
  mesh::Vertex v[3];
  mesh.face_vertices(f, v);
  for (int i = 0; i < 3; ++i) out[i] = mesh.position(v[i]);
}

// Closest point on segment ab; t is the weight of b.
Point closest_on_segment(const Point& p, const Point& a, const Point& b, double& t) {
  Vec3 ab = b - a;
  double len2 = glm::dot(ab, ab);
  t = len2 > 0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return a + t * ab;
}

// Degenerate triangle: the closest point lies on one of its three edges.
Point closest_on_edges(const Point& p, const Point& a, const Point& b, const Point& c, double bary[3]) {
  double t[3];
  Point q[3] = {closest_on_segment(p, a, b, t[0]), closest_on_segment(p, b, c, t[1]),
                closest_on_segment(p, c, a, t[2])};
  int best = 0;
  double best_d2 = glm::dot(p - q[0], p - q[0]);
  for (int i = 1; i < 3; ++i) {
    double d2 = glm::dot(p - q[i], p - q[i]);
    if (d2 < best_d2) best_d2 = d2, best = i;
  }
  // Edge i runs from corner i to corner (i+1)%3.
  bary[0] = bary[1] = bary[2] = 0.0;
  bary[best] = 1.0 - t[best];
  bary[(best + 1) % 3] = t[best];
  return q[best];
}

}  // namespace

Vec3 face_normal(const mesh::SurfaceMesh& mesh, mesh::Face f) {
  Point p[3];
  corners(mesh, f, p);
  Vec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
  double len = glm::length(n);
  return len > 0 ? n / len : Vec3(0.0);
}

double face_area(const mesh::SurfaceMesh& mesh, mesh::Face f) {
  Point p[3];
  corners(mesh, f, p);
  return 0.5 * glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
}

void triangle_angles(const Point& a, const Point& b, const Point& c, double out_rad[3]) {
  Vec3 ab = b - a, ac = c - a, bc = c - b;
  // One cross-product magnitude for all three corners: it is twice the area whichever
  // corner it is taken at, and sharing it keeps the three angles consistent.
  double dbl_area = glm::length(glm::cross(ab, ac));
  out_rad[0] = portable::atan2(dbl_area, glm::dot(ab, ac));
  out_rad[1] = portable::atan2(dbl_area, -glm::dot(ab, bc));
  out_rad[2] = portable::atan2(dbl_area, glm::dot(ac, bc));
}

double cotan(const Vec3& u, const Vec3& v) {
  double sin_scaled = glm::length(glm::cross(u, v));
  double cos_scaled = glm::dot(u, v);
  if (sin_scaled == 0.0 && cos_scaled == 0.0) return 0.0;  // a zero-length vector
  // Clamp via |cos| > kMaxCotan * sin rather than dividing first: no inf/NaN on the way.
  if (std::abs(cos_scaled) >= kMaxCotan * sin_scaled) return cos_scaled > 0 ? kMaxCotan : -kMaxCotan;
  return cos_scaled / sin_scaled;
}

Point closest_point_on_triangle(const Point& p, const Point& a, const Point& b, const Point& c, double bary[3]) {
  // Walk the Voronoi regions of the corners, then the edges, then the face interior,
  // using only dot products of the edges with p's offsets (no normal needed).
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  // The region tests below compare products whose difference is ~sin(angle) * L^4; for a
  // (nearly) collinear triangle round-off decides them, so such a triangle is treated as
  // the union of its edges, which is what it is.
  const Vec3 n = glm::cross(ab, ac);
  const double n2 = glm::dot(n, n);
  if (!(n2 > 1e-20 * glm::dot(ab, ab) * glm::dot(ac, ac))) return closest_on_edges(p, a, b, c, bary);
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) {
    bary[0] = 1, bary[1] = 0, bary[2] = 0;
    return a;
  }
  const Vec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) {
    bary[0] = 0, bary[1] = 1, bary[2] = 0;
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0 && d1 - d3 > 0) {
    double t = d1 / (d1 - d3);
    bary[0] = 1 - t, bary[1] = t, bary[2] = 0;
    return a + t * ab;
  }
  const Vec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) {
    bary[0] = 0, bary[1] = 0, bary[2] = 1;
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0 && d2 - d6 > 0) {
    double t = d2 / (d2 - d6);
    bary[0] = 1 - t, bary[1] = 0, bary[2] = t;
    return a + t * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0 && (d4 - d3) + (d5 - d6) > 0) {
    double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    bary[0] = 0, bary[1] = 1 - t, bary[2] = t;
    return b + t * (c - b);
  }
  // Inside: project on the plane. vb / |n|^2 would lose digits as eps / sin^2 on slivers;
  // the projection and the signed sub-areas below lose only eps / sin.
  const Point q = p - (glm::dot(ap, n) / n2) * n;
  const double wa = glm::dot(glm::cross(b - q, c - q), n), wb = glm::dot(glm::cross(c - q, a - q), n);
  const double wc = glm::dot(glm::cross(a - q, b - q), n), sum = wa + wb + wc;
  bary[0] = wa / sum, bary[1] = wb / sum, bary[2] = wc / sum;
  return q;
}

double detour_bound(const Point& a, const Point& c, const Point& b) {
  const Vec3 ab = b - a, ac = c - a;
  const double ab2 = glm::dot(ab, ab);
  const Vec3 height = ab2 > 0 ? ac - (glm::dot(ac, ab) / ab2) * ab : ac;
  return glm::length(height);
}

Point closest_point_on_segment(const Point& p, const Point& a, const Point& b) {
  double t;
  return closest_on_segment(p, a, b, t);
}

}  // namespace adasculpt::geometry
