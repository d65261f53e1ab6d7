#pragma once
// What a mesh's feature lines force on any remesh that keeps them: where two feature (or boundary)
// edges meet at a vertex at a small angle, every triangle filling the sector between them has an
// angle at that vertex no larger than the sector's. A remesher that preserves features cannot do
// better there, so "min angle >= 20 degrees wherever the input allows it" (issue 17) is judged
// against min(20, the smallest such sector) (adasculpt stats --features, scripts/sweep_remesh.py).
#include <cstdint>
#include <vector>

#include "mesh/surface_mesh.h"

namespace adasculpt::remesh {

// The feature marks (1 per edge slot) a remesher with this feature angle (degrees; 0 = features
// off: the boundary edges only) gives the mesh: the same rule, lone folds and three-edge loops dropped.
std::vector<std::uint8_t> feature_edge_marks(const mesh::SurfaceMesh& mesh, double feature_angle_deg);

struct FeatureSector {
  double angle_deg = 360;  // 360: no vertex has two marked edges with faces between them
  mesh::Vertex vertex;     // where the smallest sector is
};

// The smallest angle, over all vertices, between two marked edges consecutive around the vertex,
// summed over the face corners between them (a boundary's gap is not a sector).
FeatureSector smallest_feature_sector(const mesh::SurfaceMesh& mesh, const std::vector<std::uint8_t>& edge_marks);

}  // namespace adasculpt::remesh
