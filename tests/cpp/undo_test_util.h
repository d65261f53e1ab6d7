#pragma once
// For the tests of the undo log and of saved states: an exact slot-for-slot comparison of two
// meshes, and random strokes on the unit sphere.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "deform/handle_transform.h"
#include "mesh/surface_mesh.h"
#include "sculpt/session.h"

namespace adasculpt::test {

// Every built-in array (positions, connectivity, deletion flags) byte for byte, the slot counts
// and the deletion counters: what an exact undo must bring back.
inline ::testing::AssertionResult same_slots(const mesh::SurfaceMesh& a, const mesh::SurfaceMesh& b) {
  auto& ma = const_cast<mesh::SurfaceMesh&>(a);
  auto& mb = const_cast<mesh::SurfaceMesh&>(b);
  mesh::PropertyContainer* ca[] = {&ma.vertex_properties(), &ma.halfedge_properties(), &ma.edge_properties(),
                                   &ma.face_properties()};
  mesh::PropertyContainer* cb[] = {&mb.vertex_properties(), &mb.halfedge_properties(), &mb.edge_properties(),
                                   &mb.face_properties()};
  for (int k = 0; k < 4; ++k) {
    if (ca[k]->size() != cb[k]->size())
      return ::testing::AssertionFailure() << "slot counts differ (kind " << k << "): " << ca[k]->size() << " vs "
                                           << cb[k]->size();
    for (size_t i = 0; i < ca[k]->n_arrays(); ++i) {
      mesh::BasePropertyArray* x = ca[k]->array(i);
      if (x->name().size() < 2 || x->name()[1] != ':') continue;  // the built-in arrays only
      mesh::BasePropertyArray* y = cb[k]->find(x->name());
      if (!y) return ::testing::AssertionFailure() << "missing array " << x->name();
      if (ca[k]->size() && std::memcmp(x->raw(), y->raw(), ca[k]->size() * x->element_bytes()) != 0)
        return ::testing::AssertionFailure() << "array " << x->name() << " differs";
    }
  }
  const auto da = a.deleted_counts(), db = b.deleted_counts();
  if (da.vertices != db.vertices || da.edges != db.edges || da.faces != db.faces)
    return ::testing::AssertionFailure() << "deletion counters differ";
  return ::testing::AssertionSuccess();
}

struct RandomSculptor {
  std::mt19937 rng;
  explicit RandomSculptor(unsigned seed) : rng(seed) {}
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }
  int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng); }

  // A point on the unit sphere (the sculpted sphere stays near it).
  Point on_sphere() {
    Vec3 d(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    if (glm::dot(d, d) < 1e-6) d = Vec3(0, 0, 1);
    return Point(glm::normalize(d));
  }
  sculpt::BrushStroke stroke() {
    sculpt::BrushStroke s;
    s.settings.tool = deform::BrushTool(pick(7));
    s.settings.radius = uniform(0.15, 0.4);
    s.settings.strength = uniform(0.2, 0.8);
    s.settings.invert = pick(2) == 1;
    s.settings.symmetry_axis = pick(4) == 0 ? pick(3) : -1;
    const Point a = on_sphere();
    const Vec3 t = glm::normalize(glm::cross(Vec3(a), Vec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)) + Vec3(1e-3)));
    const int n = 2 + pick(6);
    for (int i = 0; i < n; ++i) s.path.push_back(Point(glm::normalize(Vec3(a) + (0.08 * i) * t)));
    return s;
  }
};

// A pull at c (handle 0.1, region 0.6) by t in `frames` drags: one undo step.
inline void pull(sculpt::Session& s, Point c, Vec3 t, int frames = 4) {
  s.grab_begin(c, 0.1, 0.6);
  for (int i = 1; i <= frames; ++i) {
    deform::HandleTransform x;
    x.translation = (double(i) / frames) * t;
    s.grab_drag(x);
  }
  s.grab_end();
}

// A save_state() blob with its chain id (bytes 12..19, new for every save) zeroed: two saves of the
// same session compare equal.
inline std::vector<uint8_t> without_chain(std::vector<uint8_t> state) {
  for (size_t i = 12; i < 20 && i < state.size(); ++i) state[i] = 0;
  return state;
}

}  // namespace adasculpt::test
