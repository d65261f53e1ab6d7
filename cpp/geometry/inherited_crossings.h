#pragma once
// Which self-intersections of a remeshed surface the input already had.
//
// A remesher cannot take a crossing out of its input: it projects onto the input, so where the
// input passes through itself the output does too, and every split there turns one crossing pair
// into several smaller ones. Judged as "output pairs minus input pairs", refining a crossing input
// counts as making new crossings (bunny at eps 0.01 %: 2 input pairs, 19 output pairs, all within
// 1 % of the diagonal of the input's own crossing). This tells those pairs from the ones the
// remesher made: an output pair is inherited when both of its faces lie in the box of one input
// crossing pair grown by the output's distance to the input (every output face lies within that
// distance of the input, so the faces that re-sample an input crossing lie in its grown box).
#include <cstddef>
#include <vector>

#include "geometry/self_intersections.h"
#include "mesh/surface_mesh.h"

namespace adasculpt::geometry {

// The pairs of `output_pairs` (faces of `output`) that are not inherited from a crossing pair of
// `input_pairs` (faces of `input`); `margin` is the growth of the input pairs' boxes, e.g. the
// Hausdorff distance between the two surfaces. With `found`, their positions in output_pairs.pairs
// are appended there (where to look).
size_t count_crossings_not_inherited(const mesh::SurfaceMesh& output, const SelfIntersectionReport& output_pairs,
                                     const mesh::SurfaceMesh& input, const SelfIntersectionReport& input_pairs,
                                     double margin, std::vector<size_t>* found = nullptr);

}  // namespace adasculpt::geometry
