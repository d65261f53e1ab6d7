#pragma once
// Polygons of more than three corners, as OFF, OBJ and PLY files list them. The readers cut each
// into a fan from its first corner as they read (append_polygon), which is exact for a convex
// polygon; a non-convex one (an L-shaped face of a CAD part) gets fan triangles outside its
// outline that fold over the rest. triangulate_concave_polygons then cuts those again by ear
// clipping, in place, so the triangles keep their order in the file.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "io/polygon_soup.h"

namespace adasculpt::io::detail {

// Appends the fan (v0, vi, vi+1) and, for four or more corners, notes the polygon for
// triangulate_concave_polygons.
void append_polygon(PolygonSoup& soup, const uint32_t* idx, size_t n);

// Cuts every noted polygon that is not convex in its own plane (the plane of its Newell normal)
// into triangles inside its outline; each keeps its n - 2 triangle slots. A polygon that no ear
// clipping fits (its outline crosses itself in that plane) keeps its fan. Clears the notes.
// Returns the number of polygons cut again.
size_t triangulate_concave_polygons(PolygonSoup& soup);

// Ear clipping of one simple polygon given by its corners in the plane, counter-clockwise:
// appends n - 2 triangles of indices into `corners`, each the ear with the largest smallest
// angle among those whose triangle holds no other corner. False (with `out` unchanged) when
// no ear is left before the end (a self-crossing or clockwise outline), or the corner tests
// run out (an untrusted file's pathological outline; polygon_triangulation.cpp).
bool ear_clip(const std::vector<std::array<double, 2>>& corners, std::vector<std::array<uint32_t, 3>>& out);

}  // namespace adasculpt::io::detail
