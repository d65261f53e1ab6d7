#include "geometry/inherited_crossings.h"

#include <algorithm>
#include <vector>

#include <glm/common.hpp>

namespace adasculpt::geometry {

namespace {

struct Box {
  Point lo, hi;
  bool meets(const Box& b) const {
    return glm::all(glm::lessThanEqual(lo, b.hi)) && glm::all(glm::lessThanEqual(b.lo, hi));
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

// Where the two faces of a crossing pair can meet: the overlap of their boxes.
Box overlap_box(const mesh::SurfaceMesh& m, std::pair<std::uint32_t, std::uint32_t> p) {
  const Box a = face_box(m, p.first), b = face_box(m, p.second);
  return {glm::max(a.lo, b.lo), glm::min(a.hi, b.hi)};
}

}  // namespace

size_t count_crossings_not_inherited(const mesh::SurfaceMesh& output, const SelfIntersectionReport& output_pairs,
                                     const mesh::SurfaceMesh& input, const SelfIntersectionReport& input_pairs,
                                     double margin, std::vector<size_t>* found) {
  // The input pairs' grown overlap boxes sorted by their low x: one that meets an output pair's
  // box starts at most the widest grown box's width before that box and not after its end.
  std::vector<Box> grown;
  grown.reserve(input_pairs.pairs.size());
  double widest = 0;
  for (const auto& p : input_pairs.pairs) {
    Box b = overlap_box(input, p);
    b.lo -= Vec3(margin);
    b.hi += Vec3(margin);
    widest = std::max(widest, b.hi.x - b.lo.x);
    grown.push_back(b);
  }
  std::sort(grown.begin(), grown.end(), [](const Box& a, const Box& b) { return a.lo.x < b.lo.x; });
  size_t not_inherited = 0;
  for (size_t i = 0; i < output_pairs.pairs.size(); ++i) {
    const Box b = overlap_box(output, output_pairs.pairs[i]);
    auto it = std::lower_bound(grown.begin(), grown.end(), b.lo.x - widest,
                               [](const Box& g, double x) { return g.lo.x < x; });
    bool inherited = false;
    for (; it != grown.end() && it->lo.x <= b.hi.x && !inherited; ++it) inherited = it->meets(b);
    if (inherited) continue;
    ++not_inherited;
    if (found) found->push_back(i);
  }
  return not_inherited;
}

}  // namespace adasculpt::geometry
