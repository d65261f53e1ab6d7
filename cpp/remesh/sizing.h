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

}  // namespace adasculpt::remesh
