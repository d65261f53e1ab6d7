// The mirror map a session keeps through every change (geometry::MirrorTracker): after random
// sequences of symmetric and one-sided strokes, grabs, undos, redos, masks and feature settings it
// must be find_mirror_map's answer (or "not symmetric" when that finds none), and a symmetric stroke
// that takes it must give the mesh a stroke that searches gives, slot for slot.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "geometry/mirror_symmetry.h"
#include "geometry/position_index.h"
#include "kept_remesher_test_util.h"
#include "mesh/build_from_triangles.h"
#include "mesh/primitives.h"
#include "remesh/remesher.h"
#include "sculpt/session.h"
#include "undo_test_util.h"

namespace adasculpt {
namespace {

// The session's map against a search over the whole mesh: equal on every live slot, or both none.
::testing::AssertionResult map_as_searched(sculpt::Session& s, int axis) {
  const std::vector<mesh::Vertex>* kept = s.mirror_map(axis);
  const std::vector<mesh::Vertex> searched = geometry::find_mirror_map(s.mesh(), axis);
  if (!kept || searched.empty()) {
    if (!kept && searched.empty()) return ::testing::AssertionSuccess() << "not symmetric";
    return ::testing::AssertionFailure() << (kept ? "kept a map, the search finds none" : "kept none, the search finds one");
  }
  if (kept->size() < s.mesh().vertices_size()) return ::testing::AssertionFailure() << "the kept map is short";
  for (mesh::Vertex v : s.mesh().vertices())
    if ((*kept)[v.idx] != searched[v.idx])
      return ::testing::AssertionFailure() << "vertex " << v.idx << ": kept " << (*kept)[v.idx].idx << ", searched "
                                           << searched[v.idx].idx;
  return ::testing::AssertionSuccess() << "symmetric";
}

TEST(GeometryPositionIndex, FollowsRandomMovesExactly) {
  mesh::SurfaceMesh m = mesh::make_icosphere(2);
  geometry::PositionIndex index;
  ASSERT_TRUE(index.build(m));
  std::mt19937 rng(3);
  std::vector<Point> spots;  // positions vertices jump to: several land on one spot
  for (mesh::Vertex v : m.vertices())
    if (v.idx % 17 == 0) spots.push_back(m.position(v));
  for (int round = 0; round < 200; ++round) {
    std::vector<mesh::Vertex> moved;
    for (int k = 0; k < 5; ++k) {
      const mesh::Vertex v(mesh::Index(rng() % m.vertices_size()));
      m.position(v) = spots[rng() % spots.size()];
      moved.push_back(v);
    }
    index.update(m, moved);
    for (const Point& p : spots) {
      int expected = 0;
      for (mesh::Vertex v : m.vertices()) expected += geometry::same_position(m.position(v), p);
      mesh::Vertex first;
      ASSERT_EQ(index.count_at(m, p, &first), expected) << "round " << round;
      if (expected > 0) {
        EXPECT_TRUE(geometry::same_position(m.position(first), p));
      }
    }
  }
}

// One random step of a session that starts on a symmetric sphere; symmetric strokes are compared
// with the same stroke in a copy of the session that searches for the map.
struct MirrorSteps {
  sculpt::Session s;
  test::RandomSculptor r;
  nlohmann::json settings = {{"epsilon", 0.002}, {"min_length", 0.03}, {"max_length", 0.2}, {"features", 0}};
  explicit MirrorSteps(unsigned seed, mesh::SurfaceMesh m = mesh::make_icosphere(4)) : r(seed) {
    s.load(std::move(m));
    s.set_settings(settings);
  }
  ::testing::AssertionResult symmetric_stroke_as_searched() {
    sculpt::BrushStroke stroke = r.stroke();
    stroke.settings.symmetry_axis = 0;
    sculpt::Session searching;
    test::copy_through_saved_state(s, searching);
    searching.set_settings(settings);
    searching.set_mirror_tracking(false);
    s.brush_stroke(stroke);
    searching.brush_stroke(stroke);
    return test::same_slots(s.mesh(), searching.mesh());
  }
  // Returns what it did. Undos come often enough that the mesh keeps coming back to symmetric.
  std::string step() {
    switch (r.pick(14)) {
      case 0:
      case 1:
      case 2:
      case 10:
      case 11: {
        const ::testing::AssertionResult same = symmetric_stroke_as_searched();
        return same ? "symmetric stroke" : std::string("symmetric stroke differs: ") + same.message();
      }
      case 3: {
        sculpt::BrushStroke stroke = r.stroke();
        stroke.settings.symmetry_axis = -1;
        s.brush_stroke(stroke);
        return "one-sided stroke";
      }
      case 4:
        test::pull(s, r.on_sphere(), 0.05 * Vec3(r.on_sphere()), 3);
        return "grab";
      case 5:
      case 6:
      case 12:
      case 13:
        return s.undo() ? "undo" : "nothing to undo";
      case 7:
        return s.redo() ? "redo" : "nothing to redo";
      case 8:
        settings["features"] = settings["features"] == 0 ? 45 : 0;
        s.set_settings(settings);
        return "features " + settings["features"].dump();
      default: {
        // Cleared, painted on one side, or painted at a point and at its mirror image (the mask
        // stays its own mirror image and strokes keep mirroring).
        const int kind = r.pick(3);
        sculpt::MaskOp op;
        op.kind = kind == 0 ? sculpt::MaskOpKind::Clear : sculpt::MaskOpKind::Paint;
        op.path = {r.on_sphere()};
        op.radius = 0.2;
        s.mask(op);
        if (kind == 2) {
          op.path[0].x = -op.path[0].x;
          s.mask(op);
        }
        return kind == 0 ? "mask cleared" : kind == 1 ? "mask painted" : "mask painted on both sides";
      }
    }
  }
};

TEST(SculptMirrorTracker, KeptMapIsTheSearchedOneThroughRandomSteps) {
  int symmetric_checks = 0, asymmetric_checks = 0;
  for (unsigned seed : {1u, 2u, 3u, 4u}) {
    MirrorSteps steps(seed);
    for (int k = 0; k < 60; ++k) {
      const std::string what = steps.step();
      const std::string where = "seed " + std::to_string(seed) + " step " + std::to_string(k) + " (" + what + ")";
      ASSERT_EQ(what.find("differs"), std::string::npos) << where;
      ASSERT_NO_THROW(steps.s.mesh().validate()) << where;
      // Asked after some steps only, so that several changes pile up between two questions.
      if (steps.r.pick(2) == 0) continue;
      const ::testing::AssertionResult same = map_as_searched(steps.s, 0);
      ASSERT_TRUE(same) << where;
      (std::string(same.message()) == "symmetric" ? symmetric_checks : asymmetric_checks) += 1;
    }
  }
  // Both answers were checked, many times.
  EXPECT_GT(symmetric_checks, 10);
  EXPECT_GT(asymmetric_checks, 10);
}

// Two open boxes at x = -1.5 and 1.5 (boundary loops and sharp edges: the feature marks
// enable_mirror makes agree across the plane), features on from the start. Vertex for vertex they
// are mirror images, triangle for triangle not (the squares' diagonals run the same way): a stroke
// that mirrors loses the symmetry on the way and hands back a map that no longer fits.
TEST(SculptMirrorTracker, OpenBoxesWithFeaturesKeepTheSearchedMap) {
  MirrorSteps steps(5, test::open_box(4, {-1.5, 1.5}));
  ASSERT_FALSE(geometry::find_mirror_map(steps.s.mesh(), 0).empty());
  steps.settings["features"] = 45;
  steps.s.set_settings(steps.settings);
  for (int k = 0; k < 10; ++k) {
    const std::string where = "round " + std::to_string(k);
    ASSERT_TRUE(steps.symmetric_stroke_as_searched()) << where;
    ASSERT_TRUE(map_as_searched(steps.s, 0)) << where;
    ASSERT_TRUE(steps.s.undo()) << where;
    const ::testing::AssertionResult back = map_as_searched(steps.s, 0);
    ASSERT_TRUE(back) << where;
    EXPECT_STREQ(back.message(), "symmetric") << where;
  }
}

// A whole pass's answer to what Session::unpaired_mirror_features keeps: every live feature edge
// whose image (across x, by find_mirror_map) is no edge or no feature, by slot.
std::vector<mesh::Edge> unpaired_by_a_pass(const mesh::SurfaceMesh& m) {
  const std::vector<mesh::Vertex> image = geometry::find_mirror_map(m, 0);
  const mesh::EdgeProperty<std::uint8_t> feature = m.get_edge_property<std::uint8_t>("remesh:feature");
  std::vector<mesh::Edge> unpaired;
  for (mesh::Edge e : m.edges()) {
    if (!feature[e]) continue;
    const mesh::Halfedge h = m.find_halfedge(image[m.vertex(e, 0).idx], image[m.vertex(e, 1).idx]);
    if (!h.is_valid() || !feature[m.edge(h)]) unpaired.push_back(e);
  }
  return unpaired;
}

// A creased sheet z = h(x, y) over [-1, 1]^2 on an n x n grid, h even in x, so that the vertices
// are mirror images across x: creases along the grid lines of 17-27 degrees, and a slight twist.
// The quads' diagonals are mirror images on the right (x > 0) of every third one on the left:
// elsewhere they run as their images' do, so the twist makes the two sides' dihedral angles differ
// a little (creases that are a feature on one side only), and those diagonals have no image.
mesh::SurfaceMesh creased_sheet(int n) {
  // Heights along a row of m grid steps (of 2 / n): the slope alternates between 0 and 0.3-0.5,
  // so that each grid line is a crease of 17-27 degrees.
  const auto crease_height = [n](int m) {
    double h = 0;
    for (int k = 0; k < m; k += 2) h += (0.3 + 0.05 * ((k * 7) % 5)) * 2.0 / n;
    return h;
  };
  std::vector<std::array<double, 3>> points;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = double(2 * i - n) / n, y = double(2 * j - n) / n, ax = std::abs(x);
      points.push_back({x, y, crease_height(std::abs(2 * i - n) / 2) + crease_height(j) + 0.4 * ax * y});
    }
  std::vector<std::array<std::uint32_t, 3>> triangles;
  const auto at = [n](int i, int j) { return std::uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if (2 * i >= n || (i + j) % 3 == 0) {  // the diagonal a-c
        triangles.push_back({a, b, c});
        triangles.push_back({a, c, d});
      } else {  // the diagonal b-d
        triangles.push_back({a, b, d});
        triangles.push_back({b, c, d});
      }
    }
  return mesh::build_from_triangles(points, triangles);
}

// Remesher::note_mirror_changes at the remesher, on the creased sheet with features at 20 degrees:
// random changes that keep the vertices mirror images (a vertex and its image raised alike, or an
// edge flipped on one side only, which changes what the other side's edges have for an image), each
// followed as a session does (reset_slots, note_mirror_changes), then the unpaired feature edges
// enable_mirror finds with the map are the whole pass's.
TEST(SculptMirrorTracker, RemesherFindsTheUnpairedFeaturesAroundTheChanges) {
  mesh::SurfaceMesh m = creased_sheet(16);
  remesh::RemeshOptions o = remesh::default_options_for(m);
  o.feature_angle_deg = 20;
  remesh::Remesher r(m, o);
  std::vector<mesh::Vertex> map = geometry::find_mirror_map(m, 0);
  ASSERT_FALSE(map.empty());
  std::mt19937 rng(7);
  int changed_lists = 0;
  size_t last_size = SIZE_MAX;
  for (int round = 0; round < 400; ++round) {
    std::vector<mesh::Vertex> changed;
    if (round > 0 && rng() % 2 == 0) {
      const mesh::Vertex v(mesh::Index(rng() % m.vertices_size()));
      const double dz = 0.04 * (double(rng() % 2001) / 1000.0 - 1.0);
      m.position(v).z += dz;
      if (map[v.idx] != v) m.position(map[v.idx]).z = m.position(v).z;
      changed = {v, map[v.idx]};
    } else if (round > 0) {
      const mesh::Edge e(mesh::Index(rng() % m.edges_size()));
      if (!m.is_flip_ok(e)) continue;
      const mesh::Halfedge h = m.halfedge(e, 0), g = m.halfedge(e, 1);
      changed = {m.to_vertex(h), m.to_vertex(g), m.to_vertex(m.next(h)), m.to_vertex(m.next(g))};
      m.flip(e);
    }
    r.reset_slots(changed);
    r.note_mirror_changes(changed);
    const std::vector<mesh::Edge> expected = unpaired_by_a_pass(m);
    r.enable_mirror(0, map);
    const std::vector<mesh::Edge>* kept = r.mirror_unpaired_features();
    ASSERT_NE(kept, nullptr);
    std::vector<mesh::Edge> sorted = *kept;
    r.disable_mirror(&map);
    ASSERT_EQ(map.size(), m.vertices_size()) << "round " << round;
    std::sort(sorted.begin(), sorted.end(), [](mesh::Edge a, mesh::Edge b) { return a.idx < b.idx; });
    ASSERT_EQ(sorted.size(), expected.size()) << "round " << round;
    for (size_t i = 0; i < expected.size(); ++i) ASSERT_EQ(sorted[i].idx, expected[i].idx) << "round " << round;
    changed_lists += expected.size() != last_size;
    last_size = expected.size();
  }
  EXPECT_GT(changed_lists, 20);  // the changes kept changing which edges are unpaired
}

// With features on, the strokes' remesher finds the unpaired feature edges (those enable_mirror's
// union marks across the plane, or whose missing image stops the mirroring) from the slots changed
// since its last check, not from every edge: after random steps on two open boxes that are mirror
// images vertex for vertex but not triangle for triangle (so bent strokes leave edges that are a
// feature on one side only, and edges without an image), the list is the whole pass's, and a
// symmetric stroke is the one a searching session makes. Features at 20 degrees, toggled off and
// on (45) by the steps.
TEST(SculptMirrorTracker, UnpairedFeaturesFollowRandomStepsAsAPassFindsThem) {
  int compared = 0, nonempty = 0;
  for (unsigned seed : {21u, 22u, 23u}) {
    MirrorSteps steps(seed, creased_sheet(16));
    steps.settings["features"] = 20;
    steps.s.set_settings(steps.settings);
    for (int k = 0; k < 50; ++k) {
      const std::string what = steps.step();
      const std::string where = "seed " + std::to_string(seed) + " step " + std::to_string(k) + " (" + what + ")";
      ASSERT_EQ(what.find("differs"), std::string::npos) << where;
      // Back to a symmetric mesh (one-sided strokes and grabs, and strokes whose feature edges
      // have no image, which run one-sided, leave none), so that most steps are compared.
      while (geometry::find_mirror_map(steps.s.mesh(), 0).empty() && steps.s.undo()) {
      }
      ASSERT_TRUE(map_as_searched(steps.s, 0)) << where;
      if (steps.settings["features"] == 0 || geometry::find_mirror_map(steps.s.mesh(), 0).empty()) continue;
      const std::vector<mesh::Edge>* kept = steps.s.unpaired_mirror_features(0);
      if (!kept) continue;  // a mask that is not its own image
      std::vector<mesh::Edge> sorted = *kept;
      std::sort(sorted.begin(), sorted.end(), [](mesh::Edge a, mesh::Edge b) { return a.idx < b.idx; });
      const std::vector<mesh::Edge> expected = unpaired_by_a_pass(steps.s.mesh());
      ASSERT_EQ(sorted.size(), expected.size()) << where;
      for (size_t i = 0; i < expected.size(); ++i) ASSERT_EQ(sorted[i].idx, expected[i].idx) << where;
      ++compared;
      nonempty += !expected.empty();
    }
  }
  EXPECT_GT(compared, 30);
  EXPECT_GT(nonempty, 10);  // the lists held edges, not only nothing
}

// A load prepares the map for the first symmetric stroke (the default plane, across x, then the
// last symmetric stroke's): asked right after the load, nothing is left to settle, and the stroke
// is the one a searching session makes. A mesh whose extent is lopsided keeps a witness instead.
TEST(SculptMirrorTracker, ALoadPreparesTheMapForTheFirstSymmetricStroke) {
  MirrorSteps steps(31);
  sculpt::Session& s = steps.s;
  ASSERT_NE(s.mirror_map(0), nullptr);
  EXPECT_EQ(s.mirror_settled(), 0u);
  ASSERT_TRUE(map_as_searched(s, 0));
  ASSERT_TRUE(steps.symmetric_stroke_as_searched());

  sculpt::BrushStroke across_y = steps.r.stroke();
  across_y.settings.symmetry_axis = 1;
  s.brush_stroke(across_y);
  s.load(mesh::make_icosphere(3));
  ASSERT_NE(s.mirror_map(1), nullptr);
  EXPECT_EQ(s.mirror_settled(), 0u);
  ASSERT_TRUE(map_as_searched(s, 1));

  mesh::SurfaceMesh shifted = mesh::make_icosphere(3);
  for (mesh::Vertex v : shifted.vertices()) shifted.position(v).y += 0.25;
  s.load(std::move(shifted));
  ASSERT_EQ(s.mirror_map(1), nullptr);
  EXPECT_EQ(s.mirror_settled(), 0u);
  ASSERT_TRUE(map_as_searched(s, 1));
}

// Two spheres at one place: every vertex shares its point with another, so there is no map. The
// load finds a pair of them and keeps it as the certificate: no question settles anything while
// the pair is at one point, and when a stroke moves one of them the next question finds another
// pair (or a witness) and the one after that settles nothing again.
TEST(SculptMirrorTracker, TwoVerticesAtOnePointAreFoundOnce) {
  const mesh::SurfaceMesh sphere = mesh::make_icosphere(3);
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (std::uint32_t copy = 0; copy < 2; ++copy) {
    const std::uint32_t base = std::uint32_t(points.size());
    for (mesh::Vertex v : sphere.vertices()) {
      const Point& p = sphere.position(v);
      points.push_back({p.x, p.y, p.z});
    }
    for (mesh::Face f : sphere.faces()) {
      mesh::Vertex c[3];
      sphere.face_vertices(f, c);
      triangles.push_back({base + c[0].idx, base + c[1].idx, base + c[2].idx});
    }
  }
  MirrorSteps steps(41, mesh::build_from_triangles(points, triangles));
  sculpt::Session& s = steps.s;
  ASSERT_EQ(s.mirror_map(0), nullptr);
  EXPECT_EQ(s.mirror_settled(), 0u);
  ASSERT_TRUE(map_as_searched(s, 0));
  for (int k = 0; k < 6; ++k) {
    const std::string where = "stroke " + std::to_string(k);
    if (k % 2) {
      ASSERT_TRUE(steps.symmetric_stroke_as_searched()) << where;
    } else {
      sculpt::BrushStroke one_sided = steps.r.stroke();
      one_sided.settings.symmetry_axis = -1;
      s.brush_stroke(one_sided);
    }
    ASSERT_TRUE(map_as_searched(s, 0)) << where;
    ASSERT_EQ(s.mirror_map(0), nullptr) << where;
    EXPECT_EQ(s.mirror_settled(), 0u) << where;
  }
}

// A sphere moved off the plane (a lopsided extent): the load keeps witnesses spread over the far
// cap, so strokes at its tip leave some of them standing and no question after them reads the mesh.
TEST(SculptMirrorTracker, StrokesAtTheTipLeaveWitnessesStanding) {
  mesh::SurfaceMesh shifted = mesh::make_icosphere(4);
  for (mesh::Vertex v : shifted.vertices()) shifted.position(v).x += 0.25;
  MirrorSteps steps(51, std::move(shifted));
  sculpt::Session& s = steps.s;
  ASSERT_EQ(s.mirror_map(0), nullptr);
  EXPECT_EQ(s.mirror_settled(), 0u);
  for (int k = 0; k < 8; ++k) {
    sculpt::BrushStroke stroke = steps.r.stroke();
    stroke.settings.symmetry_axis = 0;
    stroke.settings.radius = 0.2;
    for (Point& p : stroke.path) p = Point(1.25, 0.0, 0.0) + 0.15 * (p - Point(glm::normalize(Vec3(stroke.path[0]))));
    s.brush_stroke(stroke);
    ASSERT_TRUE(map_as_searched(s, 0)) << "stroke " << k;
    EXPECT_EQ(s.mirror_settled(), 0u) << "stroke " << k;
  }
}

// An undo of a symmetric stroke, then a symmetric stroke: the map is settled on the undo's slots
// only, and the stroke is the one a search gives. A one-sided stroke then leaves a witness: the
// next questions settle nothing.
TEST(SculptMirrorTracker, AnUndoSettlesItsSlotsAndAOneSidedStrokeLeavesAWitness) {
  MirrorSteps steps(11);
  sculpt::Session& s = steps.s;
  ASSERT_TRUE(steps.symmetric_stroke_as_searched());
  ASSERT_TRUE(map_as_searched(s, 0));
  ASSERT_TRUE(s.undo());
  ASSERT_TRUE(map_as_searched(s, 0));
  EXPECT_GT(s.mirror_settled(), 0u);
  EXPECT_LT(s.mirror_settled(), s.mesh().n_vertices() / 4);
  ASSERT_TRUE(steps.symmetric_stroke_as_searched());

  sculpt::BrushStroke one_sided = steps.r.stroke();
  one_sided.settings.symmetry_axis = -1;
  s.brush_stroke(one_sided);
  ASSERT_EQ(s.mirror_map(0), nullptr);
  EXPECT_LT(s.mirror_settled(), s.mesh().n_vertices() / 4);
  ASSERT_EQ(s.mirror_map(0), nullptr);
  EXPECT_EQ(s.mirror_settled(), 0u);  // the witness holds
  ASSERT_TRUE(steps.symmetric_stroke_as_searched());  // one-sided on this mesh, both ways
  ASSERT_TRUE(map_as_searched(s, 0));
  ASSERT_TRUE(s.undo());  // the "symmetric" stroke
  ASSERT_TRUE(s.undo());  // the one-sided one: symmetric again
  ASSERT_TRUE(map_as_searched(s, 0));
  ASSERT_NE(s.mirror_map(0), nullptr);
  ASSERT_TRUE(steps.symmetric_stroke_as_searched());
  ASSERT_TRUE(test::remesher_as_new(s));

  // A mask painted at a point and at its mirror image is its own mirror image: symmetric strokes
  // keep mirroring with the kept map (the mesh stays symmetric). Painted on one side only, it
  // stops them: the stroke runs one-sided, as with a search.
  sculpt::MaskOp op;
  op.kind = sculpt::MaskOpKind::Paint;
  op.radius = 0.3;
  op.path = {Point(glm::normalize(Vec3(0.6, 0.5, 0.3)))};
  s.mask(op);
  op.path[0].x = -op.path[0].x;
  s.mask(op);
  for (int k = 0; k < 3; ++k) {
    ASSERT_TRUE(steps.symmetric_stroke_as_searched());
    ASSERT_TRUE(geometry::is_mirror_symmetric(s.mesh(), 0));
  }
  op.path = {Point(glm::normalize(Vec3(0.3, -0.5, 0.6)))};
  s.mask(op);
  ASSERT_NE(s.mirror_map(0), nullptr);
  ASSERT_TRUE(steps.symmetric_stroke_as_searched());
}

}  // namespace
}  // namespace adasculpt
