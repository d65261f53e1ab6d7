#pragma once
// Procedural meshes for tests, benchmarks and sample models.
#include "mesh/surface_mesh.h"

namespace adasculpt::mesh {

// Subdivided icosahedron projected on a sphere: 20 * 4^subdivisions triangles.
SurfaceMesh make_icosphere(int subdivisions, double radius = 1.0);
// A flat n x n grid of squares (two triangles each) in the z = 0 plane, side `size`,
// centred at the origin: an open mesh with one boundary loop.
SurfaceMesh make_grid(int n, double size = 1.0);
// An axis-aligned box [-sx/2, sx/2] x ... with each face cut into n_x x n_y x n_z squares.
SurfaceMesh make_box(int nx, int ny, int nz, double sx = 1.0, double sy = 1.0, double sz = 1.0);

}  // namespace adasculpt::mesh
