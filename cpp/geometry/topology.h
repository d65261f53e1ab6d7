#pragma once
// Global topological and size figures of a mesh: what the quality report prints and what
// the remesher must preserve (it may never change the genus or the boundary count).
#include "mesh/surface_mesh.h"

namespace adasculpt::geometry {

// Closed loops of boundary halfedges (holes and outer borders).
int boundary_loops(const mesh::SurfaceMesh& mesh);
// Edge-connected components; isolated vertices are not counted.
int components(const mesh::SurfaceMesh& mesh);
// (2 * components - euler - boundary_loops) / 2, euler = V - E + F over non-isolated
// vertices. Defined for open meshes too: a disc has genus 0, a torus with a hole genus 1.
int genus(const mesh::SurfaceMesh& mesh);
// Diagonal of the axis-aligned bounding box of the live vertices; 0 for an empty mesh.
double bounding_box_diagonal(const mesh::SurfaceMesh& mesh);

}  // namespace adasculpt::geometry
