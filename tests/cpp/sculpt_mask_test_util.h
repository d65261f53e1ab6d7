#pragma once
// Helpers of the mask tests: a sphere with a masked cap, and what "left alone" means.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

#include "mesh/primitives.h"
#include "mesh/vertex_mask.h"
#include "sculpt/session.h"

namespace adasculpt::test {

// Everything masked, then erased around the south pole: vertices above z = 0.28 keep mask 1
// (the erase stamp is 1.6 wide, solid over its inner 0.8), those near the pole get 0, a soft band
// lies in between.
inline void mask_north_cap(sculpt::Session& s) {
  sculpt::MaskOp fill;
  fill.kind = sculpt::MaskOpKind::Fill;
  s.mask(fill);
  sculpt::MaskOp erase;
  erase.kind = sculpt::MaskOpKind::Erase;
  erase.path = {Point(0, 0, -1)};
  erase.radius = 1.6;
  erase.strength = 1;
  s.mask(erase);
}

// The positions of the fully masked vertices, sorted (slot numbers change when a stroke's end
// compacts the mesh; positions of masked vertices must not change at all).
inline std::vector<std::array<double, 3>> masked_positions(const mesh::SurfaceMesh& m) {
  const mesh::VertexProperty<float> mask = mesh::find_mask(m);
  std::vector<std::array<double, 3>> out;
  for (mesh::Vertex v : m.vertices())
    if (mesh::fully_masked(mask, v)) out.push_back({m.position(v).x, m.position(v).y, m.position(v).z});
  std::sort(out.begin(), out.end());
  return out;
}

// The triangles whose corners are all fully masked, each as its corners' positions from the
// smallest, sorted: a remeshing pass that touched one would change this list.
inline std::vector<std::array<double, 9>> masked_triangles(const mesh::SurfaceMesh& m) {
  const mesh::VertexProperty<float> mask = mesh::find_mask(m);
  std::vector<std::array<double, 9>> out;
  for (mesh::Face f : m.faces()) {
    mesh::Vertex c[3];
    m.face_vertices(f, c);
    if (!mesh::fully_masked(mask, c[0]) || !mesh::fully_masked(mask, c[1]) || !mesh::fully_masked(mask, c[2]))
      continue;
    std::array<std::array<double, 3>, 3> p;
    for (int i = 0; i < 3; ++i) p[i] = {m.position(c[i]).x, m.position(c[i]).y, m.position(c[i]).z};
    const int first = int(std::min_element(p.begin(), p.end()) - p.begin());  // keeps the orientation
    std::array<double, 9> t;
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) t[3 * i + k] = p[(first + i) % 3][k];
    out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace adasculpt::test
