// The undo history as a log of slot changes (sculpt/undo_log.h): thousands of random strokes,
// grabs, whole remeshes, undos and redos, each state compared slot for slot (positions,
// connectivity, deletion marks, numbering) with a copy saved when it was current, the mesh valid
// throughout; the log never needs its whole-mesh fallback for strokes and grabs; memory per step
// follows the changed region; save_state/restore_state reproduce the slots and the history.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "deform/handle_transform.h"
#include "io/load_mesh.h"
#include "mesh/build_from_triangles.h"
#include "mesh/primitives.h"
#include "sculpt/session.h"
#include "sculpt_test_util.h"
#include "undo_test_util.h"

using namespace adasculpt;
using adasculpt::test::RandomSculptor;
using adasculpt::test::same_slots;

namespace {

TEST(SculptUndoLog, RandomStrokesGrabsUndosAndRedosAreExactToTheSlot) {
  sculpt::Session s;
  s.load(mesh::make_icosphere(3));
  // Finer and coarser than the sphere's edges in places: strokes split and collapse.
  s.set_settings({{"epsilon", "0.2%"}, {"min_length", "2%"}, {"max_length", "6%"}});
  s.set_history_verification(true);  // the log compares its whole copy with the mesh after every change
  RandomSculptor r(18);
  std::vector<mesh::SurfaceMesh> undo_model{}, redo_model{};
  int strokes = 0, grabs = 0, remeshes = 0, undos = 0, redos = 0;
#ifdef NDEBUG
  const int kOperations = 2500;
#else
  const int kOperations = 600;  // the Debug + ASan/UBSan run of CI: 2,500 took 126 s there
#endif
  for (int op = 0; op < kOperations; ++op) {
    const int kind = r.pick(100);
    const mesh::SurfaceMesh before = s.mesh();
    const std::string at = "operation " + std::to_string(op) + " (kind " + std::to_string(kind) + ")";
    SCOPED_TRACE(at);
    if (kind < 45) {
      const sculpt::BrushStroke stroke = r.stroke();
      try {
        s.brush_stroke(stroke);
      } catch (const std::runtime_error&) {  // a stroke stopped by its face budget is still one step
      } catch (const std::logic_error& e) {
        FAIL() << at << " tool " << int(stroke.settings.tool) << " symmetry " << stroke.settings.symmetry_axis << ": "
               << e.what();
      }
      ++strokes;
    } else if (kind < 55) {
      s.grab_begin(r.on_sphere(), 0.05, r.uniform(0.2, 0.6));
      const Vec3 pull = 0.2 * Vec3(r.on_sphere());
      for (int i = 1; i <= 3; ++i) {
        deform::HandleTransform t;
        t.translation = (i / 3.0) * pull;
        s.grab_drag(t);
        if (r.pick(2)) s.clear_changes();  // the viewer reads changes between frames
      }
      s.grab_end();
      ++grabs;
    } else if (kind < 57) {
      s.remesh(1);
      ++remeshes;
    } else if (kind < 80) {
      if (s.undo()) {
        ++undos;
        ASSERT_FALSE(undo_model.empty()) << at;
        ASSERT_TRUE(same_slots(s.mesh(), undo_model.back())) << at << ": undo";
        redo_model.push_back(before);
        undo_model.pop_back();
      } else {
        ASSERT_TRUE(undo_model.empty()) << at;
      }
      s.mesh().validate();
      continue;
    } else {
      if (s.redo()) {
        ++redos;
        ASSERT_FALSE(redo_model.empty()) << at;
        ASSERT_TRUE(same_slots(s.mesh(), redo_model.back())) << at << ": redo";
        undo_model.push_back(before);
        redo_model.pop_back();
      } else {
        ASSERT_TRUE(redo_model.empty()) << at;
      }
      s.mesh().validate();
      continue;
    }
    s.mesh().validate();
    // Every stroke, grab and remesh is one step, even one that changed nothing.
    undo_model.push_back(before);
    redo_model.clear();
    while (undo_model.size() > s.undo_steps()) undo_model.erase(undo_model.begin());
    ASSERT_EQ(s.redo_steps(), 0u) << at;
  }
  EXPECT_EQ(s.history_full_diffs(), 0u) << "a stroke or grab changed slots outside the neighbourhood of its region";
  EXPECT_GT(strokes, 800 * kOperations / 2500);
  EXPECT_GT(grabs, 150 * kOperations / 2500);
  EXPECT_GT(undos, 300 * kOperations / 2500);
  EXPECT_GT(redos, 100 * kOperations / 2500);
  EXPECT_GT(remeshes, 10 * kOperations / 2500);
  // Unwinding everything still lands on every saved state.
  while (s.undo()) {
    ASSERT_TRUE(same_slots(s.mesh(), undo_model.back()));
    undo_model.pop_back();
  }
}

using test::sphere_copies;

// A step holds what it changed, not the mesh: the same stroke on the first of 1 or 16 spheres
// makes a step of the same size, a small fraction of the mesh.
TEST(SculptUndoLog, AStepHoldsTheChangedRegionNotTheMesh) {
  auto step_bytes = [](int copies) {
    sculpt::Session s;
    s.load(sphere_copies(copies));
    s.set_settings({{"epsilon", 0.002}, {"min_length", 0.03}, {"max_length", 0.06}});
    sculpt::BrushStroke st;
    st.settings.tool = deform::BrushTool::Draw;
    st.settings.radius = 0.2;
    for (int i = 0; i < 8; ++i) st.path.push_back(Point(glm::normalize(Vec3(0.05 * i, 0, 1))));
    const size_t before = s.memory_bytes();
    s.brush_stroke(st);
    EXPECT_EQ(s.undo_steps(), 1u);
    return std::pair<size_t, size_t>(s.memory_bytes() - before, before);
  };
  const auto [one_step, one_mesh] = step_bytes(1);
  const auto [many_step, many_mesh] = step_bytes(16);
  EXPECT_LT(one_step * 5, one_mesh) << one_step << " bytes for a short stroke on " << one_mesh;
  EXPECT_GT(many_mesh, 15 * one_mesh);
  EXPECT_EQ(many_step, one_step) << "the other spheres are not part of the step";
}

// save_state/restore_state: the slots (deleted ones and numbering included) and every step.
TEST(SculptUndoLog, RestoredStateIsExactToTheSlot) {
  sculpt::Session a;
  a.load(mesh::make_icosphere(3));
  a.set_settings({{"epsilon", "0.2%"}, {"min_length", "2%"}, {"max_length", "6%"}});
  RandomSculptor r(7);
  std::vector<mesh::SurfaceMesh> states{a.mesh()};
  for (int i = 0; i < 8; ++i) {
    a.brush_stroke(r.stroke());
    states.push_back(a.mesh());
  }
  a.remesh(1);
  states.push_back(a.mesh());
  for (int i = 0; i < 3; ++i) {
    a.brush_stroke(r.stroke());
    states.push_back(a.mesh());
  }
  ASSERT_TRUE(a.undo() && a.undo());
  const std::vector<uint8_t> blob = a.save_state();
  sculpt::Session b;
  b.restore_state(blob.data(), blob.size());
  ASSERT_TRUE(same_slots(b.mesh(), a.mesh()));
  EXPECT_EQ(test::without_chain(b.save_state()), test::without_chain(blob));
  size_t at = states.size() - 3;
  while (b.undo()) ASSERT_TRUE(same_slots(b.mesh(), states[--at])) << "undo to state " << at;
  EXPECT_EQ(at, 0u);
  while (b.redo()) ASSERT_TRUE(same_slots(b.mesh(), states[++at])) << "redo to state " << at;
  EXPECT_EQ(at, states.size() - 1);
}

}  // namespace
