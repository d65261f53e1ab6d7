#pragma once
// Exact orientation predicates: the sign of a determinant of double coordinates, always
// correct, never affected by rounding. A floating-point evaluation with a forward error
// bound answers almost every call; only when the result is too close to zero to trust is
// the determinant recomputed exactly with floating-point expansions (sums of
// non-overlapping doubles, error-free transformations: two-sum and fma-based two-product).
//
// Exactness matters for intersection tests on meshes: neighbouring triangles of a flat
// region are exactly coplanar, and a rounded determinant would randomly call them
// crossing or separated.
#include "mesh/types.h"

namespace adasculpt::geometry {

// Sign (+1, 0, -1) of dot(cross(b - a, c - a), d - a): +1 when d lies on the side of the
// plane abc that the right-hand normal of (a, b, c) points to, 0 when the four points are
// coplanar.
int orient3d(const Point& a, const Point& b, const Point& c, const Point& d);

// Sign of cross(b - a, c - a) in the plane: +1 when a, b, c turn counter-clockwise.
int orient2d(double ax, double ay, double bx, double by, double cx, double cy);

}  // namespace adasculpt::geometry
