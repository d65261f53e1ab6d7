#pragma once
// Per-triangle geometry: normals, areas, angles, cotangents and closest points. These are
// the building blocks of every other geometry routine, so they are written to stay finite
// on degenerate (zero-area, zero-length-edge) triangles, which real scans contain.
#include <algorithm>

#include <glm/geometric.hpp>

#include "mesh/surface_mesh.h"
#include "mesh/types.h"

namespace adasculpt::geometry {

// Squared sine of the smallest angle of a triangle (0 when degenerate). The smallest angle is
// at most 60 degrees, where the sine grows with the angle, so this orders triangles by their
// smallest angle without square roots or trigonometry: the remesher's inner loops call it per edge,
// a grab's release per face of its footprint.
inline double min_angle_sin2(const Point& a, const Point& b, const Point& c) {
  const Vec3 ab = b - a, bc = c - b, ca = a - c;
  const double lab = glm::dot(ab, ab), lbc = glm::dot(bc, bc), lca = glm::dot(ca, ca);
  const Vec3 n = glm::cross(ab, -ca);
  const double twice_area_sq = glm::dot(n, n);
  // The smallest angle is opposite the shortest edge, between the two others.
  double others;
  if (lab <= lbc && lab <= lca)
    others = lbc * lca;
  else if (lbc <= lca)
    others = lab * lca;
  else
    others = lab * lbc;
  return others > 0 ? twice_area_sq / others : 0.0;
}

// Unit normal of a face (right-hand rule on its halfedge order); the zero vector for a
// triangle of zero area.
Vec3 face_normal(const mesh::SurfaceMesh& mesh, mesh::Face f);
double face_area(const mesh::SurfaceMesh& mesh, mesh::Face f);

// The interior angles (radians) at a, b and c. atan2(|u x v|, u.v) keeps full precision for
// angles near 0 and pi, where acos of a normalised dot product loses half its digits.
// A zero-area triangle yields angles from {0, pi}.
void triangle_angles(const Point& a, const Point& b, const Point& c, double out_rad[3]);

// Cotangent of the angle between u and v, clamped to +-kMaxCotan so that a sliver gives a
// large but finite weight; 0 when u or v has zero length.
constexpr double kMaxCotan = 1e4;
double cotan(const Vec3& u, const Vec3& v);

// Whether the corners of abc are collinear, to round-off: the corner opposite the longest side
// lies within 1e-8 of the shortest side's length from that side's line (twice the area is the
// longest side times that distance), or two corners coincide. Such a triangle has no normal and
// infinite cotangents; the remesher removes it (remesh/degenerate.cpp) and the curvature does not
// use it. Relative to the shortest side, not the longest: a triangle 1e30 long and 1 wide (a stray
// vertex far away) is thin, not collinear, and reshaping it would move the surface by 1.
// The same from twice the area and the three squared side lengths, for callers that have them.
inline bool is_degenerate_triangle(double twice_area, double l0, double l1, double l2) {
  const double longest = std::max(l0, std::max(l1, l2)), shortest = std::min(l0, std::min(l1, l2));
  return twice_area * twice_area <= 1e-16 * longest * shortest;
}
inline bool is_degenerate_triangle(const Point& a, const Point& b, const Point& c) {
  const Vec3 ab = b - a, ac = c - a, bc = c - b;
  return is_degenerate_triangle(glm::length(glm::cross(ab, ac)), glm::dot(ab, ab), glm::dot(ac, ac), glm::dot(bc, bc));
}

// Closest point to p on triangle abc; bary receives its barycentric coordinates
// (weights of a, b, c, summing to 1). Exact for every Voronoi region of the triangle and
// correct for degenerate triangles (falls back to the closest point on the edges).
Point closest_point_on_triangle(const Point& p, const Point& a, const Point& b, const Point& c, double bary[3]);

// Closest point to p on segment ab (a when the segment has zero length).
Point closest_point_on_segment(const Point& p, const Point& a, const Point& b);

// An upper bound of how far the points of segment ab lie from the path a -> c -> b: the distance
// of c from the line through a and b. (The distance to side ac grows from a and the distance to
// side cb shrinks towards b; where they meet, both are at most the triangle's height over ab.)
// The fidelity check bounds an edge by a path it knows to lie on the reference.
double detour_bound(const Point& a, const Point& c, const Point& b);

}  // namespace adasculpt::geometry
