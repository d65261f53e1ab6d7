// Incremental autosave (sculpt/state_changes.h): a full state, then change records (new strokes
// and pulls, undos and redos between), restore to the live session slot for slot with the same
// undo/redo history; records cost the changed region, not the mesh; a damaged, foreign or
// out-of-order record throws and changes nothing; a whole remesh, a load or an undo past the
// saved history ask for a full state, as does the mesh's first mask (a new array); mask steps after
// it are records.
#include <gtest/gtest.h>

#include <cstring>
#include <optional>
#include <stdexcept>
#include <vector>

#include "deform/handle_transform.h"
#include "mesh/primitives.h"
#include "sculpt/session.h"
#include "undo_test_util.h"

using namespace adasculpt;
using adasculpt::test::pull;
using adasculpt::test::RandomSculptor;
using adasculpt::test::same_slots;

namespace {

using Bytes = std::vector<uint8_t>;

void restore(sculpt::Session& s, const Bytes& base, const std::vector<Bytes>& changes) {
  std::vector<sculpt::Session::ByteSpan> spans;
  for (const Bytes& c : changes) spans.push_back({c.data(), c.size()});
  s.restore_state(base.data(), base.size(), spans);
}

// A record whose checksum (its last 8 bytes, FNV-1a: state_changes.cpp) is made to match again.
Bytes reseal(Bytes r) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (size_t i = 0; i + 8 < r.size(); ++i) h = (h ^ r[i]) * 0x100000001b3ull;
  std::memcpy(r.data() + r.size() - 8, &h, 8);
  return r;
}

// b holds the same mesh, settings and history as a: every undo and redo state slot for slot.
// Both are walked back and forth and left where they were.
void expect_same_session(sculpt::Session& a, sculpt::Session& b) {
  ASSERT_TRUE(same_slots(a.mesh(), b.mesh()));
  EXPECT_EQ(a.settings().dump(), b.settings().dump());
  ASSERT_EQ(a.undo_steps(), b.undo_steps());
  ASSERT_EQ(a.redo_steps(), b.redo_steps());
  const size_t n_undo = a.undo_steps(), n_redo = a.redo_steps();
  for (size_t i = 0; i < n_undo; ++i) {
    ASSERT_TRUE(a.undo() && b.undo());
    ASSERT_TRUE(same_slots(a.mesh(), b.mesh())) << "after undo " << i + 1;
  }
  for (size_t i = 0; i < n_undo + n_redo; ++i) {
    ASSERT_TRUE(a.redo() && b.redo());
    ASSERT_TRUE(same_slots(a.mesh(), b.mesh())) << "after redo " << i + 1;
  }
  for (size_t i = 0; i < n_redo; ++i) ASSERT_TRUE(a.undo() && b.undo());
  ASSERT_TRUE(same_slots(a.mesh(), b.mesh()));
}

// Random strokes, pulls, undos and redos on a sphere, a change record after each.
struct Live {
  sculpt::Session s;
  RandomSculptor r{7};
  Bytes base;
  std::vector<Bytes> changes;
  Live() {
    s.load(mesh::make_icosphere(3));
    s.set_settings({{"epsilon", "0.2%"}, {"min_length", "2%"}, {"max_length", "6%"}});
    base = s.save_state();
  }
  void operation() {
    const int kind = r.pick(10);
    if (kind < 5) {
      try {
        s.brush_stroke(r.stroke());
      } catch (const std::runtime_error&) {  // a stroke stopped at its face budget is still a step
      }
    } else if (kind < 6) {
      pull(s, r.on_sphere(), Vec3(r.uniform(-0.2, 0.2), r.uniform(-0.2, 0.2), r.uniform(-0.2, 0.2)));
    } else if (kind < 8) {
      s.undo();
    } else {
      s.redo();
    }
  }
  void save() {
    std::optional<Bytes> c = s.save_changes();
    ASSERT_TRUE(c.has_value());
    changes.push_back(std::move(*c));
  }
};

}  // namespace

TEST(SculptStateChanges, FullStateThenRecordsRestoresTheSessionExactly) {
  Live live;
  size_t record_bytes = 0;
  for (int i = 0; i < 40; ++i) {
    live.operation();
    if (i % 3 == 2) live.s.set_settings({{"epsilon", i % 2 ? "0.25%" : "0.2%"}});  // settings ride along
    if (i % 4 != 3) live.save();  // sometimes several operations in one record
    if (!live.changes.empty()) record_bytes = std::max(record_bytes, live.changes.back().size());
    if (i % 10 == 9) {  // restore from what is saved so far, at several points
      live.save();
      sculpt::Session b;
      b.load(mesh::make_box(1, 1, 1));  // something else first: restore replaces it
      restore(b, live.base, live.changes);
      b.mesh().validate();
      expect_same_session(live.s, b);
    }
  }
  // A record is the size of a stroke's region, far below the mesh (a full state).
  EXPECT_LT(record_bytes, live.base.size() / 2) << record_bytes << " of " << live.base.size();
  EXPECT_EQ(live.s.history_full_diffs(), 0u);
}

TEST(SculptStateChanges, ARestoredSessionContinuesTheChain) {
  Live live;
  for (int i = 0; i < 6; ++i) {
    live.operation();
    live.save();
  }
  sculpt::Session b;
  restore(b, live.base, live.changes);
  // b goes on where the records end: its records follow the live ones.
  std::vector<Bytes> changes = live.changes;
  RandomSculptor r(99);
  for (int i = 0; i < 4; ++i) {
    b.brush_stroke(r.stroke());
    if (i == 2) b.undo();
    std::optional<Bytes> c = b.save_changes();
    ASSERT_TRUE(c.has_value());
    changes.push_back(std::move(*c));
  }
  sculpt::Session c;
  restore(c, live.base, changes);
  expect_same_session(b, c);
}

TEST(SculptStateChanges, TheHistoryLimitDropsTheSameOldestSteps) {
  sculpt::Session a;
  a.load(mesh::make_icosphere(4));
  const Bytes base = a.save_state();
  std::vector<Bytes> changes;
  auto save = [&] {
    std::optional<Bytes> c = a.save_changes();
    ASSERT_TRUE(c.has_value());
    changes.push_back(std::move(*c));
  };
  for (size_t i = 0; i < sculpt::Session::kMaxUndoSteps + 6; ++i) {
    a.grab_begin(Point(0, 0, 1), 0.02, 0.1);  // small steps: the records stay below the full state
    deform::HandleTransform x;
    x.translation = Vec3(0, 0, 0.002);
    a.grab_drag(x);
    a.grab_end();
    if (i % 8 == 7) save();
  }
  save();
  ASSERT_EQ(a.undo_steps(), sculpt::Session::kMaxUndoSteps);
  sculpt::Session b;
  restore(b, base, changes);
  expect_same_session(a, b);
}

TEST(SculptStateChanges, ADamagedOrStrayRecordThrowsAndChangesNothing) {
  Live live;
  for (int i = 0; i < 8; ++i) {
    pull(live.s, live.r.on_sphere(), Vec3(0, 0, 0.1));
    live.save();
  }
  sculpt::Session b;
  b.load(mesh::make_icosphere(2));
  const mesh::SurfaceMesh kept = b.mesh();
  auto refused = [&](const std::vector<Bytes>& changes, const char* what) {
    SCOPED_TRACE(what);
    try {
      restore(b, live.base, changes);
      ADD_FAILURE() << "accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind("saved state: ", 0), 0u) << e.what();
    }
    EXPECT_TRUE(same_slots(b.mesh(), kept));
    EXPECT_EQ(b.undo_steps(), 0u);
  };
  std::vector<Bytes> c = live.changes;
  c[3].resize(c[3].size() - 9);
  refused(c, "truncated");
  c = live.changes;
  c[5].push_back(0);
  refused(c, "trailing byte");
  c = live.changes;
  std::swap(c[2], c[3]);
  refused(c, "out of order");
  c = live.changes;
  c.erase(c.begin() + 4);
  refused(c, "one missing");
  c = live.changes;
  c[0][12] ^= 1;  // the chain id
  refused(c, "another chain");
  // Past the checksum (resealed): the reader's own checks. The step's deletion counters, and the
  // values of its slots (positions and connectivity) overwritten.
  c = live.changes;
  for (size_t i = c[0].size() - 48; i < c[0].size() - 16; ++i) c[0][i] = 0xff;
  refused({reseal(c[0])}, "bad counts, resealed");
  c = live.changes;
  for (size_t i = 80; i < c[0].size() - 48; i += 5) c[0][i] = 0xff;
  refused({reseal(c[0])}, "bad slot values, resealed");
  // Any flipped byte of a record is found (every 7th of the first record, a pull's step).
  for (size_t i = 0; i < live.changes[0].size(); i += 7) {
    c = live.changes;
    c[0][i] ^= 0x10;
    refused(c, "a flipped byte");
  }
  // A state of another session does not take these records.
  sculpt::Session other;
  other.load(mesh::make_icosphere(3));
  const Bytes other_base = other.save_state();
  try {
    std::vector<sculpt::Session::ByteSpan> spans{{live.changes[0].data(), live.changes[0].size()}};
    b.restore_state(other_base.data(), other_base.size(), spans);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "saved state: a change record of another saved state");
  }
  EXPECT_TRUE(same_slots(b.mesh(), kept));
  // The intact records still restore.
  restore(b, live.base, live.changes);
  expect_same_session(live.s, b);
}

TEST(SculptStateChanges, WholeMeshChangesAndUndoPastTheSavedHistoryNeedAFullState) {
  sculpt::Session s;
  EXPECT_THROW(s.save_changes(), std::logic_error);  // no mesh
  s.load(mesh::make_icosphere(3));
  EXPECT_FALSE(s.save_changes().has_value());  // nothing saved yet
  pull(s, Point(0, 0, 1), Vec3(0, 0, 0.2));
  s.save_state();
  pull(s, Point(1, 0, 0), Vec3(0.2, 0, 0));
  EXPECT_TRUE(s.save_changes().has_value());
  s.remesh(1);
  EXPECT_FALSE(s.save_changes().has_value());
  s.save_state();
  EXPECT_TRUE(s.save_changes().has_value());  // nothing new: an empty record
  s.load(mesh::make_icosphere(2));
  EXPECT_FALSE(s.save_changes().has_value());
  // A full state without history (budget 0): the pull before it cannot be undone by a reader.
  pull(s, Point(0, 0, 1), Vec3(0, 0, 0.2));
  const Bytes base = s.save_state(0);
  pull(s, Point(1, 0, 0), Vec3(0.2, 0, 0));
  ASSERT_TRUE(s.undo());
  const std::optional<Bytes> one = s.save_changes();  // the new pull and its undo: fine
  ASSERT_TRUE(one.has_value());
  sculpt::Session b;
  restore(b, base, {*one});
  EXPECT_TRUE(same_slots(s.mesh(), b.mesh()));
  EXPECT_EQ(b.undo_steps(), 0u);
  EXPECT_EQ(b.redo_steps(), 1u);
  ASSERT_TRUE(s.undo());  // past what the full state kept
  EXPECT_FALSE(s.save_changes().has_value());
  // Mid-grab: refused, as save_state.
  s.save_state();
  s.grab_begin(Point(0, 0, 1), 0.1, 0.5);
  EXPECT_THROW(s.save_changes(), std::logic_error);
  s.grab_end();
  EXPECT_TRUE(s.save_changes().has_value());
}

TEST(SculptStateChanges, MaskStepsAreRecordsOnceTheMeshHasItsMask) {
  sculpt::Session a;
  a.load(mesh::make_icosphere(3));
  a.save_state();
  sculpt::MaskOp fill;
  fill.kind = sculpt::MaskOpKind::Fill;
  a.mask(fill);  // the mesh gets its mask array: a record cannot add one
  EXPECT_FALSE(a.save_changes().has_value());
  const Bytes base = a.save_state();
  sculpt::MaskOp invert;
  invert.kind = sculpt::MaskOpKind::Invert;
  a.mask(invert);
  pull(a, Point(0, 0, 1), Vec3(0, 0, 0.2));
  a.undo();
  a.mask(fill);
  const std::optional<Bytes> c = a.save_changes();
  ASSERT_TRUE(c.has_value());
  sculpt::Session b;
  restore(b, base, {*c});
  expect_same_session(a, b);
}
