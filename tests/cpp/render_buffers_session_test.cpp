// RenderBuffers driven by a Session, frame by frame as the viewer does: after random strokes,
// grabs, undos and redos (splits, collapses and flips every frame) the incremental buffers equal
// a full rebuild and every face slot whose triangle changed is in the update's dirty list, and a frame's update costs its change, not the mesh: the same stroke on 1 and
// 16 copies of a sphere does the same buffer work.
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cstddef>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "mesh/primitives.h"
#include "render_buffers_test_util.h"
#include "sculpt/render_buffers.h"
#include "sculpt/session.h"
#include "sculpt_test_util.h"

using namespace adasculpt;
using adasculpt::test::expect_matches_rebuild;

namespace {

// The viewer's bounds, grown by each update's box as web/mesh-buffers.js does.
struct Bounds {
  float lo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, hi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
  void grow(const sculpt::RenderChanges& c) {
    if (c.rebuilt) *this = Bounds{};
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], c.box_min[k]);
      hi[k] = std::max(hi[k], c.box_max[k]);
    }
  }
  // Every live vertex inside, as drawn.
  void expect_holds(const mesh::SurfaceMesh& m, const sculpt::RenderBuffers& rb) const {
    for (mesh::Vertex v : m.vertices())
      for (int k = 0; k < 3; ++k) {
        const float x = rb.positions()[3 * v.idx + k];
        ASSERT_TRUE(lo[k] <= x && x <= hi[k]) << "vertex " << v.idx << " outside the grown bounds";
      }
  }
};

// The triangle each face slot draws (its corners' positions; zeros for an empty slot), as a picking
// structure over the slots sees it.
std::vector<float> drawn_triangles(const sculpt::RenderBuffers& rb, std::uint32_t slots) {
  std::vector<float> out(9 * size_t(slots), 0.0f);
  for (std::uint32_t f = 0; f < std::min(slots, rb.face_count()); ++f) {
    const std::uint32_t* t = rb.indices() + 3 * size_t(f);
    if (t[0] == t[1]) continue;
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) out[9 * size_t(f) + 3 * c + k] = rb.positions()[3 * size_t(t[c]) + k];
  }
  return out;
}

// Every face slot whose drawn triangle changed is in the handed-over dirty list (or all are dirty).
size_t frames_with_dirty_list = 0;  // checked frames that listed slots (not "all dirty")
void expect_dirty_faces_cover(const std::vector<float>& before, const std::vector<float>& after,
                              const sculpt::RenderBuffers& rb) {
  if (rb.all_faces_dirty()) return;
  if (rb.dirty_face_count() > 0) ++frames_with_dirty_list;
  std::vector<bool> listed(after.size() / 9, false);
  for (size_t i = 0; i < rb.dirty_face_count(); ++i)
    if (rb.dirty_faces()[i] < listed.size()) listed[rb.dirty_faces()[i]] = true;
  for (size_t f = 0; f < listed.size(); ++f)
    for (int k = 0; k < 9; ++k)
      if (before[9 * f + k] != after[9 * f + k]) {
        ASSERT_TRUE(listed[f]) << "face slot " << f << " changed but is not in the dirty list";
        break;
      }
}

// The viewer's frame: upload what changed, forget it. Returns the update's work. With `dirty`, also
// checks the update's list of dirty face slots against the drawn triangles before and after (a
// pass over the slots: tests only).
size_t frame(sculpt::Session& s, sculpt::RenderBuffers& rb, size_t* deleted_faces = nullptr,
             Bounds* bounds = nullptr, bool dirty = false) {
  if (deleted_faces) *deleted_faces += s.changes().touched_faces.size();
  const std::uint32_t slots = std::max<std::uint32_t>(rb.face_count(), std::uint32_t(s.mesh().faces_size()));
  const std::vector<float> before = dirty ? drawn_triangles(rb, slots) : std::vector<float>();
  rb.update(s.mesh(), s.changes());
  s.clear_changes();
  const sculpt::RenderChanges c = rb.take_pending();
  if (bounds) bounds->grow(c);
  if (dirty) expect_dirty_faces_cover(before, drawn_triangles(rb, slots), rb);
  return rb.last_work();
}

// A short stroke on the unit sphere centred at `centre`, starting towards `dir`.
sculpt::BrushStroke stroke_at(const Point& centre, const Vec3& dir, const Vec3& along, deform::BrushTool tool,
                              double radius) {
  sculpt::BrushStroke st;
  st.settings.tool = tool;
  st.settings.radius = radius;
  st.settings.strength = 0.7;
  for (int i = 0; i < 6; ++i) st.path.push_back(centre + glm::normalize(dir + (0.07 * i) * along));
  return st;
}

// One stroke, a frame per pointer sample; the summed update work.
size_t stroke_frames(sculpt::Session& s, sculpt::RenderBuffers& rb, const sculpt::BrushStroke& st,
                     size_t* deleted_faces = nullptr, const char* where = "stroke", Bounds* bounds = nullptr) {
  size_t work = 0;
  s.brush_begin(st.settings);
  for (const Point& p : st.path) {
    s.brush_stamp(p);
    work += frame(s, rb, deleted_faces, bounds, bounds != nullptr);
    expect_matches_rebuild(s.mesh(), rb, where);
  }
  s.brush_end();
  work += frame(s, rb, deleted_faces, bounds);
  return work;
}

}  // namespace

TEST(RenderBuffersSession, RandomStrokesGrabsUndosMatchRebuildEveryFrame) {
  sculpt::Session s;
  s.load(mesh::make_icosphere(3));
  // Finer and coarser than the sphere's edges in places: strokes split and collapse.
  s.set_settings({{"epsilon", "0.2%"}, {"min_length", "2%"}, {"max_length", "6%"}});
  sculpt::RenderBuffers rb;
  rb.rebuild(s.mesh());
  s.clear_changes();
  std::mt19937 rng(5);
  auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  auto direction = [&] {
    Vec3 d(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    return glm::dot(d, d) < 1e-6 ? Vec3(0, 0, 1) : glm::normalize(d);
  };
  size_t deleted_faces = 0;
  int undos = 0, redos = 0, grabs = 0;
  Bounds bounds;
  bounds.grow(rb.take_pending());
  for (int op = 0; op < 120; ++op) {
    const std::string at = "operation " + std::to_string(op);
    SCOPED_TRACE(at);
    const int kind = int(rng() % 10);
    if (kind < 5) {
      const auto tool = deform::BrushTool(rng() % 7);
      stroke_frames(s, rb, stroke_at(Point(0.0), direction(), direction(), tool, uniform(0.15, 0.4)), &deleted_faces,
                    at.c_str(), &bounds);
    } else if (kind < 7) {
      s.grab_begin(Point(direction()), 0.05, uniform(0.2, 0.6));
      const Vec3 pull = 0.25 * direction();
      for (int i = 1; i <= 4; ++i) {
        deform::HandleTransform t;
        t.translation = (i / 4.0) * pull;
        s.grab_drag(t);
        frame(s, rb, &deleted_faces, &bounds, true);
        expect_matches_rebuild(s.mesh(), rb, "grab frame");
      }
      s.grab_end();
      frame(s, rb, &deleted_faces, &bounds);
      ++grabs;
    } else if (kind < 9) {
      undos += s.undo() ? 1 : 0;
      EXPECT_FALSE(s.changes().everything) << "a stroke's undo is incremental";
      frame(s, rb, &deleted_faces, &bounds, true);
    } else {
      redos += s.redo() ? 1 : 0;
      frame(s, rb, &deleted_faces, &bounds, true);
    }
    expect_matches_rebuild(s.mesh(), rb, at.c_str());
    bounds.expect_holds(s.mesh(), rb);
    if (HasFatalFailure()) return;
  }
  s.mesh().validate();
  // The run exercised what the buffers cannot see from the vertices: deleted face slots.
  EXPECT_GT(deleted_faces, 100u);
  EXPECT_GT(undos, 5);
  EXPECT_GT(redos, 3);
  EXPECT_GT(grabs, 5);
  EXPECT_GT(frames_with_dirty_list, 200u);  // the list, not "all dirty", was checked
}

// The counter behind "O(changed faces), not O(face slots)": the same stroke, undo and redo on the
// first of 1 or 16 sphere copies (same slots there, detail relative to the object under the
// brush) do the same buffer work to the slot. A pass over the slots would differ 16-fold.
TEST(RenderBuffersSession, AFramesWorkFollowsTheChangeNotTheMesh) {
  size_t work[2] = {0, 0}, undo_work[2] = {0, 0}, redo_work[2] = {0, 0}, faces[2] = {0, 0};
  const int copies[2] = {1, 16};
  for (int i = 0; i < 2; ++i) {
    sculpt::Session s;
    s.load(test::sphere_copies(copies[i]));
    s.set_settings({{"min_length", "1%"}, {"max_length", "2%"}});  // finer than the sphere: strokes split
    sculpt::RenderBuffers rb;
    rb.rebuild(s.mesh());
    s.clear_changes();
    faces[i] = s.mesh().faces_size();
    // Draw, then flatten it back down, which collapses what the first stroke split.
    work[i] += stroke_frames(s, rb, stroke_at(Point(0.0), Vec3(0, 0, 1), Vec3(0, 1, 0), deform::BrushTool::Draw, 0.3));
    work[i] +=
        stroke_frames(s, rb, stroke_at(Point(0.0), Vec3(0, 0, 1), Vec3(0, 1, 0), deform::BrushTool::Smooth, 0.35));
    ASSERT_TRUE(s.undo());
    undo_work[i] = frame(s, rb);
    ASSERT_TRUE(s.redo());
    redo_work[i] = frame(s, rb);
    expect_matches_rebuild(s.mesh(), rb, "after the redo");
  }
  EXPECT_EQ(faces[1], 16 * faces[0]);
  EXPECT_GT(work[0], 0u);
  EXPECT_EQ(work[1], work[0]);
  EXPECT_EQ(undo_work[1], undo_work[0]);
  EXPECT_EQ(redo_work[1], redo_work[0]);
  // And both strokes' frames together touch far fewer slots than one pass over the scene.
  EXPECT_LT(work[1], faces[1] / 4);
}

// The buffers made for a loaded mesh have room for the slots the next strokes add: the first stroke
// after a load neither reallocates them (every view into them would go stale and the viewer would
// send the whole mesh again, a per-mesh cost in the first stroke; issue 18) nor moves them.
TEST(RenderBuffersSession, TheFirstStrokeAfterALoadKeepsTheBuffers) {
  sculpt::Session s;
  s.load(mesh::make_icosphere(4));
  s.set_settings({{"min_length", "1%"}, {"max_length", "2%"}});  // finer than the sphere: strokes split
  sculpt::RenderBuffers rb;
  ASSERT_TRUE(rb.update(s.mesh(), s.changes()).rebuilt);  // the load's full upload
  s.clear_changes();
  rb.take_pending();
  const size_t faces_before = s.mesh().faces_size();
  const float* positions = rb.positions();
  const std::uint32_t* indices = rb.indices();
  const sculpt::BrushStroke st = stroke_at(Point(0.0), Vec3(0, 0, 1), Vec3(0, 1, 0), deform::BrushTool::Draw, 0.3);
  s.brush_begin(st.settings);
  for (const Point& p : st.path) {
    s.brush_stamp(p);
    const sculpt::RenderChanges& c = rb.update(s.mesh(), s.changes());
    s.clear_changes();
    EXPECT_FALSE(c.reallocated);
    EXPECT_FALSE(c.rebuilt);
  }
  s.brush_end();
  EXPECT_FALSE(rb.update(s.mesh(), s.changes()).reallocated);
  EXPECT_GT(s.mesh().faces_size(), faces_before) << "the stroke was meant to add faces";
  EXPECT_EQ(rb.positions(), positions);
  EXPECT_EQ(rb.indices(), indices);
  expect_matches_rebuild(s.mesh(), rb, "after the first stroke");
}
