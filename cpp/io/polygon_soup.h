#pragma once
// The in-memory result of reading any mesh file: raw positions and triangles,
// with no connectivity built yet. Readers validate indices and coordinates, so a
// PolygonSoup coming out of read_soup() is safe to hand to the mesh builder.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace adasculpt::io {

struct PolygonSoup {
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<uint32_t, 3>> triangles;  // polygons already cut (io/polygon_triangulation.h)
  std::vector<std::string> warnings;               // e.g. "welded 1234 coincident STL vertices"
  // While reading only (read_soup_from_memory empties them): the polygons of four or more corners,
  // for io/polygon_triangulation.h, each its first triangle's index and its corners in
  // polygon_corners from first_corner to the next one's (or the end).
  struct Polygon {
    uint32_t first_triangle;
    uint32_t first_corner;
  };
  std::vector<Polygon> polygons;
  std::vector<uint32_t> polygon_corners;
};

}  // namespace adasculpt::io
