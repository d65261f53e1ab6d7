#pragma once
// For the tests of the session's kept remesher (Remesher::reset_slots): an open box (a boundary
// loop and sharp edges), the check that the remesher a session keeps is in the state a new one
// would start in, and a copy of a session that starts with a new one.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "mesh/build_from_triangles.h"
#include "mesh/primitives.h"
#include "remesh/remesher.h"
#include "sculpt/session.h"

namespace adasculpt::test {

// A unit box cut into n x n squares per face, without its top (z = 0.5) face: one boundary loop,
// and eight sharp edges (the box's four others are the boundary). With `centres_x`, one such box
// centred at each of these x (two boxes at -c and c: two objects, mirror images across x = 0).
inline mesh::SurfaceMesh open_box(int n = 6, std::vector<double> centres_x = {0.0}) {
  const mesh::SurfaceMesh box = mesh::make_box(n, n, n);
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (double cx : centres_x) {
    const std::uint32_t base = std::uint32_t(points.size());
    for (mesh::Vertex v : box.vertices()) {
      const Point& p = box.position(v);
      points.push_back({p.x + cx, p.y, p.z});
    }
    for (mesh::Face f : box.faces()) {
      mesh::Vertex c[3];
      box.face_vertices(f, c);
      const double z = box.position(c[0]).z + box.position(c[1]).z + box.position(c[2]).z;
      if (z > 3 * 0.5 - 1e-9) continue;  // all three corners on the top face
      triangles.push_back({base + c[0].idx, base + c[1].idx, base + c[2].idx});
    }
  }
  return mesh::build_from_triangles(points, triangles);
}

// A remesher's per-slot arrays on a mesh (invalid handles when it has none).
struct RemesherArrays {
  mesh::VertexProperty<double> sizing;
  mesh::VertexProperty<std::uint8_t> vclass, scope;
  mesh::VertexProperty<std::uint32_t> hint, segment_hint;
  mesh::EdgeProperty<std::uint8_t> feature;
  explicit RemesherArrays(const mesh::SurfaceMesh& m)
      : sizing(m.get_vertex_property<double>("remesh:sizing")),
        vclass(m.get_vertex_property<std::uint8_t>("remesh:class")),
        scope(m.get_vertex_property<std::uint8_t>("remesh:scope")),
        hint(m.get_vertex_property<std::uint32_t>("remesh:hint")),
        segment_hint(m.get_vertex_property<std::uint32_t>("remesh:segment_hint")),
        feature(m.get_edge_property<std::uint8_t>("remesh:feature")) {}
  bool present() const {
    return sizing.is_valid() && vclass.is_valid() && scope.is_valid() && hint.is_valid() && segment_hint.is_valid() &&
           feature.is_valid();
  }
  void remove_from(mesh::SurfaceMesh& m) {
    m.remove_vertex_property(sizing), m.remove_vertex_property(vclass), m.remove_vertex_property(scope);
    m.remove_vertex_property(hint), m.remove_vertex_property(segment_hint), m.remove_edge_property(feature);
  }
};

// The remesher's per-slot arrays on the session's mesh (sizing, class, scope, hints, feature
// marks) equal, on every live slot, those of a new Remesher made on the same mesh with the same
// feature angle: the state a later stroke, grab, undo or redo starts from.
inline ::testing::AssertionResult remesher_as_new(const sculpt::Session& s) {
  const mesh::SurfaceMesh& kept = s.mesh();
  const RemesherArrays k(kept);
  if (!k.present()) return ::testing::AssertionFailure() << "the session keeps no remesher";
  if (kept.get_vertex_property<mesh::Vertex>("remesh:mirror").is_valid())
    return ::testing::AssertionFailure() << "the mirror map outlived the stroke";

  mesh::SurfaceMesh bare = kept;
  RemesherArrays(bare).remove_from(bare);
  remesh::RemeshOptions o = remesh::default_options_for(bare);
  o.feature_angle_deg = s.settings()["features"].get<double>();
  const remesh::Remesher fresh(bare, o);
  const RemesherArrays f(bare);
  size_t features = 0;
  for (mesh::Vertex v : kept.vertices()) {
    auto fail = [&](const char* what) {
      return ::testing::AssertionFailure() << what << " differs at vertex " << v.idx;
    };
    if (k.sizing[v] != f.sizing[v]) return fail("sizing");
    if (k.vclass[v] != f.vclass[v]) return fail("class");
    if (k.scope[v] != f.scope[v]) return fail("scope");
    if (k.hint[v] != f.hint[v]) return fail("hint");
    if (k.segment_hint[v] != f.segment_hint[v]) return fail("segment hint");
  }
  for (mesh::Edge e : kept.edges()) {
    if (k.feature[e] != f.feature[e])
      return ::testing::AssertionFailure() << "feature mark differs at edge " << e.idx << " (kept "
                                           << int(k.feature[e]) << ", new " << int(f.feature[e]) << ")";
    features += k.feature[e] != 0;
  }
  return ::testing::AssertionSuccess() << features << " feature edges";
}

// A second session holding what `s` holds (mesh slot for slot, settings, history) through a saved
// state: it starts with a new remesher, made from the mesh as it is now.
inline void copy_through_saved_state(sculpt::Session& s, sculpt::Session& copy) {
  const std::vector<std::uint8_t> state = s.save_state();
  copy.restore_state(state.data(), state.size());
}

}  // namespace adasculpt::test
