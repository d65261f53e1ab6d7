#pragma once
// Whether the triangles around one vertex surely meet only where their connectivity says they
// do: consecutive triangles along their common edge, the others at the centre alone. Then no two
// of them form a self-intersecting pair (geometry/self_intersections.h): a crossing guard may pass
// over every pair of faces that share that vertex, which are most of the pairs whose boxes touch
// (on bunny.off nine pairs in ten that the remesher's guard looked at shared a corner).
//
// The certificate: a direction n (the sum of the fan's normals) across which every triangle of
// the fan turns counter-clockwise by a margin far above rounding, and whose shadows on the plane
// across n wind around the centre exactly once. The projection along n is then one-to-one on
// each triangle, and the shadows are a star that overlaps itself nowhere, so two triangles that
// met at a point other than the centre or their common edge would cast overlapping shadows there.
// False means "not shown", never "crossing": callers test the pairs themselves.
#include <cstddef>

#include "mesh/surface_mesh.h"
#include "mesh/types.h"

namespace adasculpt::geometry {

// The closed fan of the triangles (centre, ring[i], ring[(i + 1) % k]).
bool star_surely_embedded(const Point& centre, const Point* ring, size_t k);

// The fan of a vertex of the mesh, at its current positions. False for a vertex on a border or
// with more than kMaxCertifiedValence neighbours (left to the pair tests).
constexpr size_t kMaxCertifiedValence = 64;
bool fan_surely_embedded(const mesh::SurfaceMesh& mesh, mesh::Vertex v);

}  // namespace adasculpt::geometry
