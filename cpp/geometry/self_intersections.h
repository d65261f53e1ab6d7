#pragma once
// Self-intersections of a triangle mesh: which pairs of faces cross or touch where the
// mesh's connectivity says they should not. Every test is exact (geometry/exact_predicates),
// so a count is reproducible and independent of rounding.
//
// The definition matches CGAL's Polygon_mesh_processing::self_intersections (what the
// independent judge meshq reports as "self_intersecting_pairs"):
// - faces with no common vertex count when the closed triangles share any point;
// - faces sharing exactly one vertex count when they meet anywhere else: the edge opposite
//   the shared vertex in one face meets the other face;
// - faces sharing an edge count only when they fold onto each other: coplanar, with their
//   third vertices on the same side of the shared edge;
// - degenerate faces (three collinear corners) are left out and counted separately.
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "mesh/surface_mesh.h"
#include "mesh/types.h"

namespace adasculpt::geometry {

// Whether the closed triangles p and q share at least one point. Both must be
// non-degenerate (not collinear); no connectivity is assumed.
bool triangles_intersect(const Point p[3], const Point q[3]);

// Whether the closed segment ab meets the closed, non-degenerate triangle t.
bool segment_intersects_triangle(const Point& a, const Point& b, const Point t[3]);

// Whether three points are exactly collinear (a degenerate triangle).
bool collinear(const Point& a, const Point& b, const Point& c);

// The pair test with the connectivity rules above, for triangles given by vertex indices
// into `points` (shared indices mean shared vertices). Both must be non-degenerate.
bool faces_intersect(const std::vector<Point>& points, const std::array<std::uint32_t, 3>& t,
                     const std::array<std::uint32_t, 3>& u);

// The same for triangles given by their corners and vertex ids (equal ids mean a shared vertex):
// for a triangle that does not exist yet, such as one a remeshing operation would create.
bool faces_intersect(const Point tp[3], const std::array<std::uint32_t, 3>& t, const Point up[3],
                     const std::array<std::uint32_t, 3>& u);

struct SelfIntersectionReport {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;  // face indices, first < second, sorted
  size_t degenerate_faces = 0;                                 // collinear faces, left out of the test
  bool capped = false;                                         // stopped at max_pairs
};

// All intersecting pairs of a triangle soup. A bounding volume hierarchy over the face
// boxes finds the candidate pairs; each is then tested exactly. Stops once max_pairs pairs
// are found (a badly broken mesh can have millions), setting `capped`.
SelfIntersectionReport self_intersections(const std::vector<Point>& points,
                                          const std::vector<std::array<std::uint32_t, 3>>& triangles,
                                          size_t max_pairs = SIZE_MAX);

// The same for the live faces of a mesh; pair entries are Face indices.
SelfIntersectionReport self_intersections(const mesh::SurfaceMesh& mesh, size_t max_pairs = SIZE_MAX);

}  // namespace adasculpt::geometry
