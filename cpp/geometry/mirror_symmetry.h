#pragma once
// Exact mirror symmetry of a mesh across a coordinate plane (x, y or z = 0): the pairing of every
// vertex with the vertex at its mirror image. Brush strokes with symmetry keep such a mesh
// exactly symmetric, vertex for vertex (sculpt/brush.h, remesh::Remesher::enable_mirror).
#include <vector>

#include "mesh/surface_mesh.h"

namespace adasculpt::geometry {

// The vertex at the mirror image of each vertex (indexed by vertex index; deleted slots map to an
// invalid handle) when every vertex's position with the `axis` coordinate negated is exactly
// another vertex's position (a vertex on the plane is its own image); otherwise, or when two
// vertices share a position, an empty vector. Connectivity is not compared (the remesher checks
// the image of each edge it touches): see is_mirror_symmetric. A pass over the mesh; a session
// keeps this answer through its changes at their cost instead (mirror_tracker.h).
std::vector<mesh::Vertex> find_mirror_map(const mesh::SurfaceMesh& mesh, int axis);

// Vertex for vertex and triangle for triangle: find_mirror_map succeeds and every triangle's
// mirror image, with the opposite orientation, is a triangle of the mesh.
bool is_mirror_symmetric(const mesh::SurfaceMesh& mesh, int axis);

}  // namespace adasculpt::geometry
