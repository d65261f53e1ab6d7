#include "geometry/inherited_crossings.h"

#include <algorithm>
#include <vector>

#include <glm/common.hpp>

namespace adasculpt::geometry {

namespace {

struct Box {
  Point lo, hi;
  bool contains(const Box& b) const {
    return glm::all(glm::lessThanEqual(lo, b.lo)) && glm::all(glm::lessThanEqual(b.hi, hi));
  }
};

Box face_box(const mesh::SurfaceMesh& m, std::uint32_t f) {
  mesh::Vertex v[3];
  m.face_vertices(mesh::Face(f), v);
  Box b{m.position(v[0]), m.position(v[0])};
  for (int i = 1; i < 3; ++i) {
    b.lo = glm::min(b.lo, m.position(v[i]));
    b.hi = glm::max(b.hi, m.position(v[i]));
  }
  return b;
}

Box pair_box(const mesh::SurfaceMesh& m, std::pair<std::uint32_t, std::uint32_t> p) {
  Box a = face_box(m, p.first);
  const Box b = face_box(m, p.second);
  return {glm::min(a.lo, b.lo), glm::max(a.hi, b.hi)};
}

}  // namespace

size_t count_crossings_not_inherited(const mesh::SurfaceMesh& output, const SelfIntersectionReport& output_pairs,
                                     const mesh::SurfaceMesh& input, const SelfIntersectionReport& input_pairs,
                                     double margin, std::vector<size_t>* found) {
  // The input pairs' grown boxes sorted by their low x: an output pair's box can only lie in
  // those whose low x is at most its own and whose low x is within the widest box of it.
  std::vector<Box> grown;
  grown.reserve(input_pairs.pairs.size());
  double widest = 0;
  for (const auto& p : input_pairs.pairs) {
    Box b = pair_box(input, p);
    b.lo -= Vec3(margin);
    b.hi += Vec3(margin);
    widest = std::max(widest, b.hi.x - b.lo.x);
    grown.push_back(b);
  }
  std::sort(grown.begin(), grown.end(), [](const Box& a, const Box& b) { return a.lo.x < b.lo.x; });
  size_t not_inherited = 0;
  for (size_t i = 0; i < output_pairs.pairs.size(); ++i) {
    const Box b = pair_box(output, output_pairs.pairs[i]);
    auto it = std::lower_bound(grown.begin(), grown.end(), b.lo.x - widest,
                               [](const Box& g, double x) { return g.lo.x < x; });
    bool inherited = false;
    for (; it != grown.end() && it->lo.x <= b.lo.x && !inherited; ++it) inherited = it->contains(b);
    if (inherited) continue;
    ++not_inherited;
    if (found) found->push_back(i);
  }
  return not_inherited;
}

}  // namespace adasculpt::geometry
