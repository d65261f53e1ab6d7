// The session keeps one remesher through strokes, grabs, undo and redo, and resets the slots each
// of them changed (Remesher::reset_slots) instead of making a new one with its pass over the whole
// mesh; and it follows the box of the object under the brush (ComponentBox) instead of walking the
// object after each undo. Random sequences on one or two small open boxes (a boundary, sharp
// edges, features on or off, symmetric strokes): after every step the mesh is valid and the kept
// remesher's arrays are a new one's, and a step after an undo or redo gives the same mesh, slot
// for slot, as in a copy of the session that starts with a new remesher and walks the object.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include <glm/geometric.hpp>

#include "geometry/mirror_symmetry.h"
#include "kept_remesher_test_util.h"
#include "mesh/primitives.h"
#include "sculpt/session.h"
#include "test_build.h"
#include "undo_test_util.h"

using namespace adasculpt;

namespace {

struct BoxSculptor : test::RandomSculptor {
  using RandomSculptor::RandomSculptor;

  double shift = 0;  // two boxes: at x = -shift and x = shift
  // A point on one of the open box's five faces, sharp edges and corners included.
  Point on_box() {
    Point p(uniform(-0.5, 0.5), uniform(-0.5, 0.5), uniform(-0.5, 0.5));
    const int face = pick(5);  // -x, +x, -y, +y, -z (+z is open)
    if (face < 4)
      p[face / 2] = face % 2 ? 0.5 : -0.5;
    else
      p.z = -0.5;
    p.x += pick(2) ? shift : -shift;
    return p;
  }
  Vec3 direction() {
    Vec3 d(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    return glm::dot(d, d) > 1e-6 ? glm::normalize(d) : Vec3(1, 0, 0);
  }
  // RandomSculptor's tool and settings (symmetry across x or y can be on: the box is symmetric
  // there until a one-sided stroke), on a path along the box.
  sculpt::BrushStroke stroke() {
    sculpt::BrushStroke s = RandomSculptor::stroke();
    const Point a = on_box();
    const Vec3 t = direction();
    s.path.assign(1, a);
    for (int i = 1, n = 2 + pick(5); i < n; ++i) s.path.push_back(a + (0.06 * i) * t);
    return s;
  }
};

enum class Op { Stroke, Pull, Undo, Redo };

struct Step {
  Op op;
  sculpt::BrushStroke stroke;
  Point at;
  Vec3 by;
};

Step random_step(BoxSculptor& r) {
  const int k = r.pick(10);
  Step s{k < 4 ? Op::Stroke : k < 5 ? Op::Pull : k < 8 ? Op::Undo : Op::Redo, {}, {}, {}};
  if (s.op == Op::Stroke) s.stroke = r.stroke();
  if (s.op == Op::Pull) s.at = r.on_box(), s.by = 0.1 * r.direction();
  return s;
}

// Returns whether the step was an undo or redo that changed the mesh.
bool run(sculpt::Session& s, const Step& step) {
  switch (step.op) {
    case Op::Stroke:
      try {
        s.brush_stroke(step.stroke);
      } catch (const std::runtime_error&) {  // stopped at its face budget: what was stamped stays
      }
      break;
    case Op::Pull:
      test::pull(s, step.at, step.by, 3);
      break;
    case Op::Undo:
      return s.undo();
    case Op::Redo:
      return s.redo();
  }
  return false;
}

}  // namespace

TEST(SculptKeptRemesher, RandomStrokesGrabsUndoAndRedoKeepItAsNew) {
  const int kSequences = test::operations_for_this_build(300), kSteps = 12;  // ASan: 75 sequences
  int compared = 0;
  for (int seq = 0; seq < kSequences; ++seq) {
    BoxSculptor r(1000 + seq);
    sculpt::Session s;
    // Two objects in every other pair of sequences: the detail follows the one under the brush.
    r.shift = seq % 4 < 2 ? 0.0 : 0.8;
    s.load(r.shift > 0 ? test::open_box(4, {-r.shift, r.shift}) : test::open_box(4));
    // Coarse detail keeps the meshes small; features on in half the sequences.
    s.set_settings({{"epsilon", "0.5%"}, {"min_length", "2%"}, {"max_length", "8%"}, {"features", seq % 2 ? 40 : 0}});
    // Compared after an undo or redo only: a stroke right after a stroke reuses the object size the
    // last one measured (Session: component_diagonal), which a copy measures again.
    bool after_history = false;
    for (int i = 0; i < kSteps; ++i) {
      const std::string where = "sequence " + std::to_string(seq) + ", step " + std::to_string(i);
      const Step step = random_step(r);
      bool done = false;
      if (after_history) {  // the same step in a copy that starts with a new remesher
        sculpt::Session fresh;
        test::copy_through_saved_state(s, fresh);
        run(fresh, step);
        done = run(s, step);
        ASSERT_TRUE(test::same_slots(s.mesh(), fresh.mesh())) << where << ": kept and new remesher";
        ++compared;
      } else {
        done = run(s, step);
      }
      ASSERT_NO_THROW(s.mesh().validate()) << where;
      ASSERT_TRUE(test::remesher_as_new(s)) << where;
      after_history = done;
    }
  }
  EXPECT_GT(compared, kSequences);  // about 2.4 comparisons per sequence
}

// A stroke that mirrored to its end leaves the remesher its mirror map, and the next symmetric
// stroke takes it instead of searching the mesh (Remesher::disable_mirror(true)): each stroke must
// do what it does in a copy of the session that searches, and the sphere must stay exactly
// symmetric. Lengths are given as numbers, so that no stroke scales them by the object's size (a
// copy measures it again, the session reuses the last stroke's). An undo and a one-sided stroke
// in between must make the next symmetric stroke search again.
TEST(SculptKeptRemesher, SymmetricStrokesTakeTheLastStrokesMirrorMap) {
  const nlohmann::json absolute = {{"epsilon", 0.002}, {"min_length", 0.03}, {"max_length", 0.2}};
  sculpt::Session s;
  s.load(mesh::make_icosphere(4));
  s.set_settings(absolute);
  ASSERT_TRUE(geometry::is_mirror_symmetric(s.mesh(), 0));
  test::RandomSculptor r(7);
  for (int k = 0; k < 10; ++k) {
    const std::string where = "stroke " + std::to_string(k);
    if (k == 4) {
      ASSERT_TRUE(s.undo());
    }
    sculpt::BrushStroke stroke = r.stroke();
    stroke.settings.symmetry_axis = k == 7 ? -1 : 0;  // one one-sided stroke: the sphere is not symmetric after it
    if (k == 8) {  // back to symmetric
      ASSERT_TRUE(s.undo());
    }
    sculpt::Session searching;
    test::copy_through_saved_state(s, searching);
    searching.set_settings(absolute);
    s.brush_stroke(stroke);
    searching.brush_stroke(stroke);
    ASSERT_TRUE(test::same_slots(s.mesh(), searching.mesh())) << where;
    EXPECT_EQ(geometry::is_mirror_symmetric(s.mesh(), 0), k != 7) << where;
    ASSERT_TRUE(test::remesher_as_new(s)) << where;
  }
}
