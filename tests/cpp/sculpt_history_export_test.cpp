// Session::save_state / restore_state (the browser's autosave): the mesh, the settings and the
// undo/redo history come back exactly, the history respects its byte budget (newest steps kept),
// undo/redo work after a restore, and a damaged blob (the mesh or any step of its history) changes
// nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/load_mesh.h"
#include "mesh/primitives.h"
#include "sculpt/session.h"
#include "undo_test_util.h"

using namespace adasculpt;
using adasculpt::test::pull;

namespace {

// Positions bit for bit and the same triangles (vertex indices, in face order).
::testing::AssertionResult same_geometry(const mesh::SurfaceMesh& a, const mesh::SurfaceMesh& b) {
  const io::PolygonSoup sa = io::soup_from_mesh(a), sb = io::soup_from_mesh(b);
  if (sa.points.size() != sb.points.size() || sa.triangles.size() != sb.triangles.size())
    return ::testing::AssertionFailure() << "sizes differ: " << sa.points.size() << "/" << sb.points.size()
                                         << " vertices, " << sa.triangles.size() << "/" << sb.triangles.size()
                                         << " faces";
  if (std::memcmp(sa.points.data(), sb.points.data(), sa.points.size() * sizeof(sa.points[0])) != 0)
    return ::testing::AssertionFailure() << "positions differ";
  if (sa.triangles != sb.triangles) return ::testing::AssertionFailure() << "triangles differ";
  return ::testing::AssertionSuccess();
}

// Three pulls and one undo: undo holds [input, after 1st pull], redo holds [after 3rd pull].
struct Scenario {
  sculpt::Session s;
  std::vector<mesh::SurfaceMesh> states;  // input, after pull 1, 2, 3
  Scenario() {
    s.load(mesh::make_icosphere(3));
    s.set_settings({{"epsilon", "0.1%"}, {"max_length", "8%"}, {"features", 30}});
    states.push_back(s.mesh());
    pull(s, Point(0, 0, 1), Vec3(0, 0, 0.4));
    states.push_back(s.mesh());
    pull(s, Point(1, 0, 0), Vec3(0.3, 0, 0));
    states.push_back(s.mesh());
    pull(s, Point(0, -1, 0), Vec3(0, -0.3, 0.1));
    states.push_back(s.mesh());
    EXPECT_TRUE(s.undo());
  }
};

}  // namespace

TEST(SculptHistoryExport, RestoresMeshSettingsAndHistoryExactly) {
  Scenario a;
  const std::vector<uint8_t> blob = a.s.save_state();
  sculpt::Session b;
  b.load(mesh::make_box(2, 2, 2));  // something else first: restore replaces it
  b.restore_state(blob.data(), blob.size());
  EXPECT_TRUE(same_geometry(b.mesh(), a.states[2]));
  b.mesh().validate();
  EXPECT_EQ(b.settings().dump(), a.s.settings().dump());  // absolute values and the diagonal
  EXPECT_EQ(b.undo_steps(), 2u);
  EXPECT_EQ(b.redo_steps(), 1u);
  EXPECT_TRUE(b.changes().everything);
  // Redo, then undo all the way back: every state bit for bit.
  EXPECT_TRUE(b.redo());
  EXPECT_TRUE(same_geometry(b.mesh(), a.states[3]));
  EXPECT_FALSE(b.redo());
  EXPECT_TRUE(b.undo() && b.undo());
  EXPECT_TRUE(same_geometry(b.mesh(), a.states[1]));
  EXPECT_TRUE(b.undo());
  EXPECT_TRUE(same_geometry(b.mesh(), a.states[0]));
  EXPECT_FALSE(b.undo());
  // Saving the restored session gives the same blob (nothing lost or reordered on the way).
  EXPECT_TRUE(b.redo() && b.redo());
  EXPECT_EQ(test::without_chain(b.save_state()), test::without_chain(blob));  // the chain id is new per save
}

TEST(SculptHistoryExport, SculptingContinuesAfterARestore) {
  Scenario a;
  const std::vector<uint8_t> blob = a.s.save_state();
  sculpt::Session b;
  b.restore_state(blob.data(), blob.size());
  pull(b, Point(-1, 0, 0), Vec3(-0.3, 0, 0));
  b.mesh().validate();
  EXPECT_FALSE(b.can_redo());  // a new step drops the redo branch
  EXPECT_EQ(b.undo_steps(), 3u);
  EXPECT_TRUE(b.undo());
  EXPECT_TRUE(same_geometry(b.mesh(), a.states[2]));
}

TEST(SculptHistoryExport, HistoryIsBoundedNewestStepsFirst) {
  Scenario a;
  const std::vector<uint8_t> full = a.s.save_state();
  const std::vector<uint8_t> none = a.s.save_state(0);
  const size_t current = none.size();
  ASSERT_GT(full.size(), current);

  sculpt::Session b;
  b.restore_state(none.data(), none.size());
  EXPECT_EQ(b.undo_steps(), 0u);
  EXPECT_EQ(b.redo_steps(), 0u);
  EXPECT_TRUE(same_geometry(b.mesh(), a.states[2]));

  // The smallest budget that keeps a step is the newest undo step's serialized size; it keeps
  // only that step (the oldest would need more).
  size_t lo = 0, hi = full.size() - current;  // save_state(lo) keeps nothing, save_state(hi) keeps a step
  while (hi - lo > 1) {
    const size_t mid = (lo + hi) / 2;
    (a.s.save_state(mid).size() > current ? hi : lo) = mid;
  }
  const size_t newest_step = hi;
  const std::vector<uint8_t> one = a.s.save_state(newest_step);
  EXPECT_EQ(one.size(), current + newest_step);
  b.restore_state(one.data(), one.size());
  EXPECT_EQ(b.undo_steps(), 1u);
  EXPECT_EQ(b.redo_steps(), 0u);
  EXPECT_TRUE(b.undo());
  EXPECT_TRUE(same_geometry(b.mesh(), a.states[1]));
  EXPECT_FALSE(b.undo());

  // One byte less keeps nothing; the full budget keeps all three steps.
  EXPECT_EQ(a.s.save_state(newest_step - 1).size(), current);
  EXPECT_LE(full.size() - current, sculpt::Session::kDefaultStateHistoryBytes);
}

TEST(SculptHistoryExport, DamagedBlobsThrowAndChangeNothing) {
  Scenario a;
  const std::vector<uint8_t> blob = a.s.save_state();
  sculpt::Session b;
  b.load(mesh::make_icosphere(1));
  pull(b, Point(0, 0, 1), Vec3(0, 0, 0.2));
  const mesh::SurfaceMesh before = b.mesh();
  const std::string settings = b.settings().dump();
  auto expect_rejected = [&](std::vector<uint8_t> bad, const char* what) {
    EXPECT_THROW(b.restore_state(bad.data(), bad.size()), std::invalid_argument) << what;
    EXPECT_TRUE(same_geometry(b.mesh(), before)) << what;
    EXPECT_EQ(b.settings().dump(), settings) << what;
    EXPECT_EQ(b.undo_steps(), 1u) << what;
  };
  expect_rejected(std::vector<uint8_t>(blob.begin(), blob.begin() + blob.size() / 2), "truncated");
  expect_rejected(std::vector<uint8_t>(blob.begin(), blob.end() - 1), "last byte missing");
  std::vector<uint8_t> extra = blob;
  extra.push_back(0);
  expect_rejected(extra, "trailing byte");
  std::vector<uint8_t> magic = blob;
  magic[0] = 'X';
  expect_rejected(magic, "magic");
  std::vector<uint8_t> version = blob;
  version[8] = 99;
  expect_rejected(version, "version");
  expect_rejected({}, "empty");
  // The n-th array of that name in the blob (arrays are written as u16 name length, name,
  // u32 element size, u64 byte count, bytes): the offset of its first element.
  auto array_data = [&](const std::string& name, int nth) {
    size_t at = 0;
    for (int k = 0; k <= nth; ++k) {
      auto it = std::search(blob.begin() + at, blob.end(), name.begin(), name.end());
      EXPECT_NE(it, blob.end()) << name << " #" << nth;
      at = size_t(it - blob.begin()) + name.size();
    }
    return at + 4 + 8;
  };
  // The current mesh's first halfedge pointing to a vertex that does not exist.
  std::vector<uint8_t> index = blob;
  std::memset(&index[array_data("h:connectivity", 0)], 0xff, 4);
  expect_rejected(index, "index out of range");
  // A history step whose first moved vertex is at NaN: restoring visits every state of the
  // history, so the blob is refused as a whole.
  std::vector<uint8_t> bad_step = blob;
  std::memset(&bad_step[array_data("v:point", 1)], 0xff, 8);
  expect_rejected(bad_step, "a step with a non-finite position");
  // A step whose connectivity is broken.
  std::vector<uint8_t> bad_links = blob;
  std::memset(&bad_links[array_data("h:connectivity", 1)], 0x00, 16);
  expect_rejected(bad_links, "a step with broken connectivity");
}

TEST(SculptHistoryExport, RefusedWithoutAMeshOrDuringAGrab) {
  sculpt::Session s;
  EXPECT_THROW(s.save_state(), std::logic_error);
  s.load(mesh::make_icosphere(2));
  s.grab_begin(Point(0, 0, 1), 0.1, 0.5);
  EXPECT_THROW(s.save_state(), std::logic_error);
  s.grab_end();
  EXPECT_NO_THROW(s.save_state());
  EXPECT_GT(s.memory_bytes(), s.mesh().n_faces() * 8);
}
