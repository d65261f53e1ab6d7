// RenderBuffers: incremental updates must leave exactly what a full rebuild writes, report
// ranges that cover every change, and keep their storage (views) until they say otherwise.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <utility>
#include <vector>

#include "mesh/primitives.h"
#include "mesh/surface_mesh.h"
#include "sculpt/render_buffers.h"
#include "sculpt/session.h"
#include "render_buffers_test_util.h"

#include <glm/geometric.hpp>

using namespace adasculpt;
using namespace adasculpt::mesh;
using adasculpt::sculpt::RenderBuffers;
using adasculpt::sculpt::RenderChanges;
using adasculpt::test::expect_matches_rebuild;

namespace {

// Same fields as sculpt::ChangeSet.
struct Changes {
  Changes() = default;
  Changes(bool topology, bool all, std::vector<Vertex> vertices, std::vector<Face> faces = {})
      : topology_changed(topology), everything(all), touched_vertices(std::move(vertices)),
        touched_faces(std::move(faces)) {}
  bool topology_changed = false;
  bool everything = false;
  std::vector<Vertex> touched_vertices;
  std::vector<Face> touched_faces;
};

// The faces a collapse of h deletes (what the remesher logs in ChangeSet::touched_faces).
std::vector<Face> faces_of_edge(const SurfaceMesh& m, Halfedge h) {
  std::vector<Face> out;
  for (Halfedge g : {h, m.opposite(h)})
    if (!m.is_boundary(g)) out.push_back(m.face(g));
  return out;
}

bool in_range(std::uint32_t i, std::uint32_t b, std::uint32_t e) { return b <= i && i < e; }

}  // namespace

TEST(RenderBuffers, RebuildWritesPositionsIndicesAndOutwardNormals) {
  SurfaceMesh m = make_icosphere(3, 2.0);
  RenderBuffers rb;
  const RenderChanges& c = rb.rebuild(m);
  EXPECT_TRUE(c.reallocated);
  EXPECT_TRUE(c.indices_changed);
  EXPECT_EQ(c.vertex_count, m.vertices_size());
  EXPECT_EQ(c.face_count, m.faces_size());
  EXPECT_EQ(c.vertex_end, m.vertices_size());
  EXPECT_EQ(c.face_end, m.faces_size());
  EXPECT_GE(rb.vertex_capacity(), m.vertices_size());
  for (Vertex v : m.vertices()) {
    const float* p = rb.positions() + 3 * v.idx;
    const float* n = rb.normals() + 3 * v.idx;
    EXPECT_FLOAT_EQ(p[0], float(m.position(v).x));
    double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    EXPECT_NEAR(len, 1.0, 1e-5);
    // Sphere centred at the origin: the normal is the direction of the position.
    double d = (n[0] * p[0] + n[1] * p[1] + n[2] * p[2]) / 2.0;
    EXPECT_GT(d, 0.999);
  }
  for (Face f : m.faces()) {
    Vertex fv[3];
    m.face_vertices(f, fv);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(rb.indices()[3 * f.idx + k], fv[k].idx);
  }
}

TEST(RenderBuffers, MovingOneVertexRefreshesItsRingOnly) {
  SurfaceMesh m = make_icosphere(4);
  RenderBuffers rb;
  rb.rebuild(m);
  const float* positions_before = rb.positions();
  Vertex v(100);
  m.position(v) *= 1.2;
  const RenderChanges& c = rb.update(m, Changes{false, false, {v}});
  EXPECT_FALSE(c.reallocated);
  EXPECT_FALSE(c.indices_changed);
  EXPECT_EQ(c.face_begin, c.face_end);
  EXPECT_TRUE(in_range(v.idx, c.vertex_begin, c.vertex_end));
  for (Vertex w : m.vertices(v)) EXPECT_TRUE(in_range(w.idx, c.vertex_begin, c.vertex_end));
  EXPECT_EQ(rb.positions(), positions_before) << "no reallocation, so views stay valid";
  expect_matches_rebuild(m, rb, "after move");
}

TEST(RenderBuffers, SplitFlipCollapseWithGarbageMatchRebuild) {
  SurfaceMesh m = make_icosphere(2);
  RenderBuffers rb;
  rb.rebuild(m);

  // Split: a new vertex (touched) and new face slots.
  Edge e(10);
  Point mid = 0.5 * (m.position(m.vertex(e, 0)) + m.position(m.vertex(e, 1)));
  Vertex s = m.split(e, mid * 1.1);
  const RenderChanges& c1 = rb.update(m, Changes{true, false, {s}});
  EXPECT_TRUE(c1.indices_changed);
  EXPECT_EQ(c1.face_count, m.faces_size());
  expect_matches_rebuild(m, rb, "after split");

  // Flip: no vertex moves; the old edge's ends are touched (the contract), their rings hold both faces.
  Edge flip_edge;
  for (Edge f : m.edges())
    if (m.is_flip_ok(f)) {
      flip_edge = f;
      break;
    }
  ASSERT_TRUE(flip_edge.is_valid());
  Vertex fa = m.vertex(flip_edge, 0), fb = m.vertex(flip_edge, 1);
  m.flip(flip_edge);
  std::vector<std::uint32_t> before(rb.indices(), rb.indices() + 3 * m.faces_size());
  const RenderChanges& c2 = rb.update(m, Changes{true, false, {fa, fb}});
  EXPECT_TRUE(c2.indices_changed);
  int changed_slots = 0;
  for (std::uint32_t f = 0; f < m.faces_size(); ++f) {
    bool same = std::equal(before.begin() + 3 * f, before.begin() + 3 * f + 3, rb.indices() + 3 * f);
    changed_slots += same ? 0 : 1;
    if (!same) { EXPECT_TRUE(in_range(f, c2.face_begin, c2.face_end)); }
  }
  EXPECT_EQ(changed_slots, 2) << "a flip rewrites the two faces of one edge";
  expect_matches_rebuild(m, rb, "after flip");

  // Collapse: deleted faces become (0,0,0) and no live vertex reaches them.
  Halfedge h;
  for (Halfedge g : m.halfedges())
    if (m.is_collapse_ok(g)) {
      h = g;
      break;
    }
  ASSERT_TRUE(h.is_valid());
  Vertex gone = m.from_vertex(h), survivor = m.to_vertex(h);
  const std::vector<Face> deleted = faces_of_edge(m, h);
  m.collapse(h);
  EXPECT_TRUE(m.is_deleted(gone));
  rb.update(m, Changes{true, false, {gone, survivor}, deleted});
  expect_matches_rebuild(m, rb, "after collapse");
  size_t zero_faces = 0;
  for (std::uint32_t f = 0; f < m.faces_size(); ++f) {
    const std::uint32_t* t = rb.indices() + 3 * f;
    if (m.is_deleted(Face(f))) {
      EXPECT_EQ(t[0] + t[1] + t[2], 0u);
      ++zero_faces;
    }
  }
  EXPECT_EQ(zero_faces, 2u);

  // Garbage collection renumbers everything: the session reports `everything`.
  m.garbage_collection();
  const RenderChanges& c4 = rb.update(m, Changes{true, true, {}});
  EXPECT_EQ(c4.vertex_count, m.vertices_size());
  EXPECT_EQ(c4.face_end, m.faces_size());
  expect_matches_rebuild(m, rb, "after garbage collection");
}

TEST(RenderBuffers, RandomEditsAlwaysMatchRebuildAndRangesCoverChanges) {
  SurfaceMesh m = make_icosphere(3);
  std::mt19937 rng(7);
  RenderBuffers rb;
  rb.rebuild(m);
  int reallocations = 0;
  for (int step = 0; step < 600; ++step) {
    // Snapshot of the previous buffers to check that the reported ranges cover every difference.
    std::vector<float> pos_before(rb.positions(), rb.positions() + 3 * size_t(rb.vertex_count()));
    std::vector<std::uint32_t> idx_before(rb.indices(), rb.indices() + 3 * size_t(rb.face_count()));

    Changes ch;
    int op = int(rng() % 4);
    if (op == 0) {  // move a few vertices
      for (int k = 0; k < 5; ++k) {
        Vertex v(rng() % m.vertices_size());
        if (m.is_deleted(v)) continue;
        m.position(v) += Vec3(0.01 * (int(rng() % 21) - 10), 0.0, 0.01);
        ch.touched_vertices.push_back(v);
      }
    } else if (op == 1) {
      Edge e(rng() % m.edges_size());
      if (m.is_deleted(e)) continue;
      Point mid = 0.5 * (m.position(m.vertex(e, 0)) + m.position(m.vertex(e, 1)));
      ch.touched_vertices.push_back(m.split(e, mid));
      ch.topology_changed = true;
    } else if (op == 2) {
      Edge e(rng() % m.edges_size());
      if (m.is_deleted(e) || !m.is_flip_ok(e)) continue;
      ch.touched_vertices = {m.vertex(e, 0), m.vertex(e, 1)};
      m.flip(e);
      ch.topology_changed = true;
    } else {
      Halfedge h(rng() % m.halfedges_size());
      if (m.is_deleted(h) || !m.is_collapse_ok(h)) continue;
      ch.touched_vertices = {m.from_vertex(h), m.to_vertex(h)};
      ch.touched_faces = faces_of_edge(m, h);
      m.collapse(h);
      ch.topology_changed = true;
    }
    const float* old_ptr = rb.positions();
    const RenderChanges c = rb.update(m, ch);
    if (c.reallocated) {
      ++reallocations;
    } else {
      EXPECT_EQ(rb.positions(), old_ptr);
      for (std::uint32_t i = 0; i < pos_before.size(); ++i)
        if (pos_before[i] != rb.positions()[i]) {
          ASSERT_TRUE(in_range(i / 3, c.vertex_begin, c.vertex_end)) << step;
        }
      for (std::uint32_t i = 0; i < idx_before.size(); ++i)
        if (idx_before[i] != rb.indices()[i]) {
          ASSERT_TRUE(in_range(i / 3, c.face_begin, c.face_end)) << step;
        }
      // New slots are always inside the reported range.
      for (std::uint32_t v = std::uint32_t(pos_before.size() / 3); v < c.vertex_count; ++v)
        if (!m.is_deleted(Vertex(v))) {
          ASSERT_TRUE(in_range(v, c.vertex_begin, c.vertex_end)) << step;
        }
    }
    expect_matches_rebuild(m, rb, "random step");
    if (HasFatalFailure()) return;
  }
  m.validate();
  EXPECT_LT(reallocations, 10) << "geometric growth: few reallocations for hundreds of splits";
}

// Undo and redo of strokes report what they touched (sculpt/undo_log.h), not everything: the
// incremental updates, arrays shrinking on undo included, match a rebuild every time.
TEST(RenderBuffers, UndoAndRedoOfStrokesUpdateIncrementally) {
  sculpt::Session s;
  s.load(make_icosphere(3));
  s.set_settings({{"min_length", "1%"}, {"max_length", "1.5%"}});  // finer than the sphere: strokes split
  RenderBuffers rb;
  rb.rebuild(s.mesh());
  s.clear_changes();
  for (int k = 0; k < 4; ++k) {
    sculpt::BrushStroke st;
    st.settings.tool = k % 2 ? deform::BrushTool::Inflate : deform::BrushTool::Draw;
    st.settings.radius = 0.3;
    for (int i = 0; i < 5; ++i) st.path.push_back(Point(glm::normalize(Vec3(0.1 * i - 0.2, 0.3 * k - 0.5, 1))));
    s.brush_stroke(st);
    rb.update(s.mesh(), s.changes());
    s.clear_changes();
  }
  expect_matches_rebuild(s.mesh(), rb, "after the strokes");
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(s.undo());
    EXPECT_FALSE(s.changes().everything);
    rb.update(s.mesh(), s.changes());
    s.clear_changes();
    expect_matches_rebuild(s.mesh(), rb, "after an undo");
  }
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(s.redo());
    EXPECT_FALSE(s.changes().everything);
    rb.update(s.mesh(), s.changes());
    s.clear_changes();
    expect_matches_rebuild(s.mesh(), rb, "after a redo");
  }
}

TEST(RenderBuffers, PendingAccumulatesUntilTaken) {
  SurfaceMesh m = make_icosphere(3);
  RenderBuffers rb;
  rb.rebuild(m);
  rb.take_pending();
  m.position(Vertex(3)) *= 1.1;
  rb.update(m, Changes{false, false, {Vertex(3)}});
  m.position(Vertex(500)) *= 1.1;
  rb.update(m, Changes{false, false, {Vertex(500)}});
  RenderChanges p = rb.take_pending();
  EXPECT_TRUE(in_range(3, p.vertex_begin, p.vertex_end));
  EXPECT_TRUE(in_range(500, p.vertex_begin, p.vertex_end));
  EXPECT_FALSE(p.reallocated);
  EXPECT_EQ(p.vertex_count, m.vertices_size());
  RenderChanges q = rb.take_pending();
  EXPECT_TRUE(q.empty());
  EXPECT_EQ(q.vertex_count, m.vertices_size());
}

// Not a timing test (never fails on speed): prints the cost of an update with and without topology.
TEST(RenderBuffers, PrintsUpdateCostOn100kFaces) {
  SurfaceMesh m = make_icosphere(6);  // 81920 faces
  RenderBuffers rb;
  rb.rebuild(m);
  std::vector<Vertex> touched;
  for (std::uint32_t i = 0; i < 2000; ++i) touched.push_back(Vertex(i * 7 % m.vertices_size()));
  for (bool topology : {false, true}) {
    auto t0 = std::chrono::steady_clock::now();
    const int frames = 20;
    for (int f = 0; f < frames; ++f) {
      for (Vertex v : touched) m.position(v) *= 1.0001;
      rb.update(m, Changes{topology, false, touched});
    }
    double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / frames;
    std::printf("[ info ] RenderBuffers::update, %zu faces, 2000 touched vertices, topology %s: %.3f ms/frame\n",
                m.faces_size(), topology ? "on" : "off", ms);
  }
  SUCCEED();
}
