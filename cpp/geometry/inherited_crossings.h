#pragma once
// Which self-intersections of a remeshed surface the input already had.
//
// A remesher cannot take a crossing out of its input: it projects onto the input, so where the
// input passes through itself the output does too, and every split there turns one crossing pair
// into several smaller ones. Judged as "output pairs minus input pairs", refining a crossing input
// counts as making new crossings (bunny at eps 0.01 %: 2 input pairs, 19 output pairs, all within
// 1 % of the diagonal of the input's own crossing). This tells those pairs from the ones the
// remesher made: two triangles can only meet inside the overlap of their boxes, so an output pair
// is inherited when its overlap box comes within `margin` of an input crossing pair's overlap box.
// With the Hausdorff distance between the surfaces as the margin's scale, a crossing the remesh
// re-sampled (moved by at most that distance) is inherited; one elsewhere is new.
#include <cstddef>
#include <vector>

#include "geometry/self_intersections.h"
#include "mesh/surface_mesh.h"

namespace adasculpt::geometry {

// The pairs of `output_pairs` (faces of `output`) that are not inherited from a crossing pair of
// `input_pairs` (faces of `input`); `margin` is how far from an input crossing an output crossing
// still counts as the same one, e.g. twice the Hausdorff distance between the two surfaces. With `found`, their positions in output_pairs.pairs
// are appended there (where to look).
size_t count_crossings_not_inherited(const mesh::SurfaceMesh& output, const SelfIntersectionReport& output_pairs,
                                     const mesh::SurfaceMesh& input, const SelfIntersectionReport& input_pairs,
                                     double margin, std::vector<size_t>* found = nullptr);

}  // namespace adasculpt::geometry
