#pragma once
// Discrete differential geometry at vertices (Meyer, Desbrun, Schroeder, Barr 2003), feeding
// the remesher's sizing field: the paper's target edge length depends on the maximal
// absolute principal curvature kappa.
#include <vector>

#include "mesh/surface_mesh.h"
#include "mesh/types.h"

namespace adasculpt::geometry {

// Mixed Voronoi area: the Voronoi cell inside non-obtuse triangles, and A/2 (obtuse at v)
// or A/4 (obtuse elsewhere) otherwise, so the areas of all vertices tile the surface.
double mixed_voronoi_area(const mesh::SurfaceMesh& mesh, mesh::Vertex v);

// Unnormalised cotan Laplacian sum_j (cot alpha_ij + cot beta_ij)(p_j - p_i). Divided by
// 2A it is the mean-curvature normal 2Hn, pointing inwards on a convex surface.
Vec3 cotan_laplacian(const mesh::SurfaceMesh& mesh, mesh::Vertex v);

// kappa = |H| + sqrt(max(H^2 - K, 0)) with H = |cotan_laplacian| / (4A) and the angle defect
// K = (2pi - sum of angles) / A. Boundary and isolated vertices give 0: their angle defect
// is not curvature, and the remesher sizes the boundary separately.
double max_abs_curvature(const mesh::SurfaceMesh& mesh, mesh::Vertex v);
// Per vertex slot (size vertices_size(), 0 for deleted slots).
void max_abs_curvature(const mesh::SurfaceMesh& mesh, std::vector<double>& out);

}  // namespace adasculpt::geometry
