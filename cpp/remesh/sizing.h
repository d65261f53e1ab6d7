#pragma once
// The paper's sizing field (section 3): the longest edge that keeps a triangle within eps of
// a surface of maximal absolute curvature kappa is L = sqrt(6 eps / kappa - 3 eps^2).
#include <cstdint>
#include <vector>

#include "mesh/surface_mesh.h"

namespace adasculpt::remesh {

// Clamped to [min_length, max_length]; flat regions (kappa = 0) get max_length. Where the
// radius of curvature is below eps (details under the tolerance) L = sqrt(3) eps, the
// formula's value at kappa = 1 / eps: L is non-decreasing in eps and non-increasing in kappa.
double sizing_from_curvature(double kappa, double epsilon, double min_length, double max_length);

// Limits how fast the sizing may grow away from small values: L(v) <= L(w) + gradation * |v - w|
// along edges. The paper's field can jump from min to max length within one input triangle
// (e.g. beside a sharp crease), which no triangle shape can follow; a bounded gradient lets the
// mesh grade smoothly and keeps the angles good. Only lowers values (never coarser than the
// paper's field, so the tolerance still holds).
// With `inside` (per vertex slot), the propagation stays among the vertices marked there.
void limit_sizing_gradation(const mesh::SurfaceMesh& mesh, const std::vector<mesh::Vertex>& vertices,
                            mesh::VertexProperty<double>& sizing, double gradation,
                            const std::vector<std::uint8_t>* inside = nullptr);

// The sizing at a point p of a reference triangle (barycentric coordinates bary) from the values at
// its corners. On a triangle about as small as its values or smaller (a scan, a remeshed surface:
// longest edge <= kCoarseTriangle x the smallest value) it is the linear interpolation. On a
// larger one the corners' values are point measurements, not a field over the triangle: a coarse
// CAD part's faces are flat inside, and only their corners, on its creases, see curvature (and
// the min length). Interpolated, those values asked for min-length edges over whole faces:
// cgal/mpi.off, 90 vertices, asked for 635k vertices at epsilon 0.05 %, min length 0.2 %. There
// each corner's value reaches as far as the gradation limit lets it: the larger of the
// interpolation and the smallest value + gradation x distance to its corner, at most max_length.
// The shared meshes at the defaults have triangles up to 4-8 times their sizing (the dragon's
// long input triangles): from 2x, the dragon's remesh lost 4 degrees of its min angle; from 4-8x
// they keep their figures (dragon 64,167 vertices against 64,180).
// (The creases between the corners are kept by the fidelity check, fidelity.cpp, which splits
// the edges that cut them.)
inline constexpr double kFineTriangle = 4.0, kCoarseTriangle = 8.0;
double sizing_inside_triangle(const Point corner[3], const double value[3], const Point& p, const double bary[3],
                              double gradation, double max_length);
// The integral of 1 / L^2 over the triangle, with L as sizing_inside_triangle gives it: the
// vertex budget's estimate (budget.cpp). Exact for the interpolation's corners' mean, sampled on a
// regular subdivision of a coarse triangle.
double inverse_square_sizing_integral(const Point corner[3], const double value[3], double gradation,
                                      double max_length);

}  // namespace adasculpt::remesh
