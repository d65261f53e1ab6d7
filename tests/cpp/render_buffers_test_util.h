#pragma once
// Shared by the render-buffer tests: the incremental buffers against a fresh rebuild.
#include <gtest/gtest.h>

#include <cstdint>

#include "mesh/surface_mesh.h"
#include "sculpt/render_buffers.h"

namespace adasculpt::test {

// Compares the incremental buffers with a fresh rebuild: live vertices and every face slot.
inline void expect_matches_rebuild(const mesh::SurfaceMesh& m, const sculpt::RenderBuffers& inc, const char* where) {
  sculpt::RenderBuffers full;
  full.rebuild(m);
  ASSERT_EQ(inc.vertex_count(), full.vertex_count()) << where;
  ASSERT_EQ(inc.face_count(), full.face_count()) << where;
  for (std::uint32_t i = 0; i < m.vertices_size(); ++i) {
    if (m.is_deleted(mesh::Vertex(i))) continue;
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(inc.positions()[3 * i + k], full.positions()[3 * i + k]) << where << " vertex " << i;
      // Circulation may start at another halfedge after an edit: same sum, other rounding.
      ASSERT_NEAR(inc.normals()[3 * i + k], full.normals()[3 * i + k], 1e-5) << where << " normal " << i;
    }
  }
  for (std::uint32_t i = 0; i < 3 * m.faces_size(); ++i) {
    ASSERT_EQ(inc.indices()[i], full.indices()[i]) << where << " index slot " << i;
  }
}

}  // namespace adasculpt::test
