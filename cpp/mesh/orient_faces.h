#pragma once
// Giving a triangle soup one orientation: files whose faces were written in random order of
// their corners (CGAL's *-shuffled.off test meshes, exports that lost their winding) describe
// a perfectly good surface whose neighbouring faces disagree about which side is out.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace adasculpt::mesh {

// Reverses faces (swaps their last two corners) so that every two faces sharing an edge use it
// in opposite directions. Each connected piece keeps its own orientation where it was already
// consistent; a piece that needed reversals faces outwards (positive volume) when it is closed,
// and keeps the orientation most of its faces had when it has a border. Edges shared by more
// than two faces are left alone (build_from_triangles refuses them).
// Throws TopologyError for a one-sided piece (a Möbius strip, a Klein bottle): no orientation
// exists. Returns how many faces were reversed.
size_t orient_faces_consistently(const std::vector<std::array<double, 3>>& points,
                                 std::vector<std::array<std::uint32_t, 3>>& faces);

}  // namespace adasculpt::mesh
