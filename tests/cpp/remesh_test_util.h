#pragma once
// Shared helper of the remeshing tests: the sweep's adaptive settings, given relative to the mesh.
#include "mesh/surface_mesh.h"
#include "remesh/remesher.h"

namespace adasculpt::test {

// Adaptive remesh at the defaults but for epsilon and min length, given as fractions of the
// bounding-box diagonal (as the CLI's "0.05%").
inline void remesh_relative(mesh::SurfaceMesh& m, double epsilon, double min_length) {
  remesh::RemeshOptions o = remesh::default_options_for(m);
  const double diagonal = remesh::bounding_box_diagonal(m);
  o.epsilon = epsilon * diagonal;
  o.min_length = min_length * diagonal;
  remesh::remesh(m, o);
}

}  // namespace adasculpt::test
