#pragma once
// Turning a triangle soup (indexed triangles, as files store them) into a SurfaceMesh.
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "mesh/surface_mesh.h"

namespace adasculpt::mesh {

// The soup cannot be a manifold surface: the message names the offending vertices
// (0-based indices of the input).
class TopologyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct BuildReport {
  std::vector<std::string> warnings;  // repairs that were made
  size_t split_vertices = 0;          // non-manifold vertices duplicated, one per extra fan
  size_t dropped_faces = 0;           // faces with a repeated vertex
  size_t unreferenced_vertices = 0;   // input vertices used by no face (not kept)
  size_t reoriented_faces = 0;        // faces reversed to agree with their neighbours
};

// Non-manifold vertices (several fans of faces meeting at one point) are split into one
// vertex per fan, a common repair reported as a warning; so is reversing faces whose
// neighbours run their common edge the same way (orient_faces.h). Non-manifold edges (three or
// more faces) and one-sided surfaces (a Moebius strip) are errors.
SurfaceMesh build_from_triangles(const std::vector<std::array<double, 3>>& points,
                                 const std::vector<std::array<std::uint32_t, 3>>& triangles,
                                 BuildReport* report = nullptr);

}  // namespace adasculpt::mesh
