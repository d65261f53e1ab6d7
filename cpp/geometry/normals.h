#pragma once
// Vertex normals weighted by the incident corner angles (Thuermer & Wuethrich): unlike
// area or uniform weights, they do not change when a face around the vertex is split,
// which matters on a mesh the remesher keeps re-triangulating.
#include <vector>

#include "mesh/surface_mesh.h"
#include "mesh/types.h"

namespace adasculpt::geometry {

// Unit normal; the zero vector for an isolated vertex or a fan of degenerate faces.
Vec3 vertex_normal(const mesh::SurfaceMesh& mesh, mesh::Vertex v);
// Per vertex slot (size vertices_size(), zero for deleted slots).
void vertex_normals(const mesh::SurfaceMesh& mesh, std::vector<Vec3>& out);

}  // namespace adasculpt::geometry
