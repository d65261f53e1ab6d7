#pragma once
// The sculpting mask: one float per vertex in [0, 1], how much of every deformation the vertex
// refuses (0 = moves freely, 1 = never moves, and the remesher leaves its triangles alone). It
// lives on the mesh as the vertex property "v:mask", created by the first mask operation
// (sculpt/mask.h), so a mesh that was never masked pays nothing. The "v:" prefix makes it one of
// the arrays the undo log records and the saved state carries (sculpt/undo_log.h), like positions.
#include "mesh/surface_mesh.h"

namespace adasculpt::mesh {

inline constexpr const char* kMaskProperty = "v:mask";

// The mesh's mask, or an invalid property when the mesh was never masked.
inline VertexProperty<float> find_mask(const SurfaceMesh& m) { return m.get_vertex_property<float>(kMaskProperty); }

// Whether v may not move at all. Callers test this rather than scaling by 1 - mask: a fully masked
// vertex must keep its position bit for bit, which p + 0 * d does not promise (d may be NaN).
inline bool fully_masked(const VertexProperty<float>& mask, Vertex v) {
  return mask.is_valid() && mask[v] >= 1.0f;
}
// The fraction of a displacement v takes (1 - mask; 1 without a mask).
inline double unmasked_fraction(const VertexProperty<float>& mask, Vertex v) {
  return mask.is_valid() ? 1.0 - double(mask[v]) : 1.0;
}

}  // namespace adasculpt::mesh
