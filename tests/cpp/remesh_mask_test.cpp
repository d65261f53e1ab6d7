// The remesher and the sculpting mask: a fully masked vertex is outside every scope, so no split,
// collapse, flip, relaxation or projection touches it or any of its triangles, in region calls (a
// sculpting frame) and in whole-mesh iterations alike; the mask follows the splits and collapses
// around partly masked vertices.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <map>
#include <vector>

#include "mesh/primitives.h"
#include "mesh/vertex_mask.h"
#include "remesh/remesher.h"

using namespace adasculpt;
using mesh::Vertex;

namespace {

// Every face at a fully masked vertex, as its corner slots from the smallest (orientation kept).
std::vector<std::array<mesh::Index, 3>> faces_at_masked(const mesh::SurfaceMesh& m) {
  const mesh::VertexProperty<float> mask = mesh::find_mask(m);
  std::vector<std::array<mesh::Index, 3>> out;
  for (mesh::Face f : m.faces()) {
    Vertex c[3];
    m.face_vertices(f, c);
    if (!mesh::fully_masked(mask, c[0]) && !mesh::fully_masked(mask, c[1]) && !mesh::fully_masked(mask, c[2])) continue;
    const int first = int(std::min_element(c, c + 3, [](Vertex a, Vertex b) { return a.idx < b.idx; }) - c);
    out.push_back({c[first].idx, c[(first + 1) % 3].idx, c[(first + 2) % 3].idx});
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::map<mesh::Index, Point> masked_positions(const mesh::SurfaceMesh& m) {
  const mesh::VertexProperty<float> mask = mesh::find_mask(m);
  std::map<mesh::Index, Point> out;
  for (Vertex v : m.vertices())
    if (mesh::fully_masked(mask, v)) out[v.idx] = m.position(v);
  return out;
}

// A sphere whose cap above z = 0.3 is masked, a band below it partly, and settings that make the
// remesher refine everything else (a quarter of the default edge length).
struct Scene {
  mesh::SurfaceMesh mesh = mesh::make_icosphere(3);
  remesh::RemeshOptions options;
  Scene() {
    auto mask = mesh.add_vertex_property<float>(mesh::kMaskProperty, 0.0f);
    for (Vertex v : mesh.vertices()) {
      const double z = mesh.position(v).z;
      mask[v] = z > 0.3 ? 1.0f : z > 0.0 ? float(z / 0.3) * 0.9f : 0.0f;
    }
    options = remesh::default_options_for(mesh);
    options.epsilon /= 16;
    options.min_length /= 4;
    options.max_length /= 4;
    faces_before = faces_at_masked(mesh);
    points_before = masked_positions(mesh);
    vertices_before = mesh.n_vertices();
  }
  std::vector<std::array<mesh::Index, 3>> faces_before;
  std::map<mesh::Index, Point> points_before;
  size_t vertices_before = 0;
};

bool same_points(const std::map<mesh::Index, Point>& a, const std::map<mesh::Index, Point>& b) {
  if (a.size() != b.size()) return false;
  for (const auto& [i, p] : a) {
    const auto it = b.find(i);
    if (it == b.end() || std::memcmp(&p, &it->second, sizeof(Point)) != 0) return false;
  }
  return true;
}

}  // namespace

// The remeshed scene: the unmasked part refined, everything at masked vertices as it was.
void expect_masked_part_untouched(const Scene& s) {
  s.mesh.validate();
  EXPECT_GT(s.mesh.n_vertices(), s.vertices_before + s.vertices_before / 2);
  EXPECT_EQ(faces_at_masked(s.mesh), s.faces_before);
  EXPECT_TRUE(same_points(masked_positions(s.mesh), s.points_before));
}

TEST(RemeshMask, RegionIterationsLeaveMaskedVerticesAndTheirTrianglesAlone) {
  Scene s;
  remesh::Remesher r(s.mesh, s.options);
  for (int i = 0; i < 4; ++i) {
    std::vector<Vertex> region;
    for (Vertex v : s.mesh.vertices()) region.push_back(v);
    r.iterate_region(region);
    s.mesh.validate();
  }
  expect_masked_part_untouched(s);
  const mesh::VertexProperty<float> mask = mesh::find_mask(s.mesh);
  size_t partly = 0;
  for (Vertex v : s.mesh.vertices()) {
    ASSERT_TRUE(mask[v] >= 0.0f && mask[v] <= 1.0f);
    partly += mask[v] > 0.0f && mask[v] < 1.0f;
  }
  EXPECT_GT(partly, 100u);  // new vertices in the band carry its mask
}

TEST(RemeshMask, WholeMeshIterationsLeaveMaskedVerticesAndTheirTrianglesAlone) {
  Scene s;
  {
    remesh::Remesher r(s.mesh, s.options);
    for (int i = 0; i < 3; ++i) r.iterate();
    r.polish();
  }
  expect_masked_part_untouched(s);
}
