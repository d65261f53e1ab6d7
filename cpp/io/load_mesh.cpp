#include "io/load_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <glm/common.hpp>

#include "mesh/build_from_triangles.h"

namespace adasculpt::io {

namespace {

// The geometry squares and multiplies lengths (areas, cotangents, curvature); beyond this range
// those products overflow or vanish and every later step would fail with a puzzling message.
constexpr double kMinExtent = 1e-60, kMaxExtent = 1e60;

void check_extent(const mesh::SurfaceMesh& m, const std::string& name) {
  Point lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (mesh::Vertex v : m.vertices()) {
    lo = glm::min(lo, m.position(v));
    hi = glm::max(hi, m.position(v));
  }
  const Vec3 extent = hi - lo;
  const double largest = std::max({std::abs(lo.x), std::abs(lo.y), std::abs(lo.z), std::abs(hi.x), std::abs(hi.y),
                                   std::abs(hi.z)});
  const double size = std::max({extent.x, extent.y, extent.z});
  if (!(size >= kMinExtent) || !(largest <= kMaxExtent)) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  ": coordinates out of the supported range (size %.3g, largest %.3g; supported %.0e to %.0e): "
                  "rescale the model",
                  size, largest, kMinExtent, kMaxExtent);
    throw IoError(name + buf);
  }
}

mesh::SurfaceMesh mesh_from_soup(const PolygonSoup& soup, const std::string& name,
                                 std::vector<std::string>* warnings) {
  mesh::BuildReport report;
  mesh::SurfaceMesh result;
  try {
    result = mesh::build_from_triangles(soup.points, soup.triangles, &report);
  } catch (const mesh::TopologyError& e) {
    throw IoError(name + ": " + e.what());
  }
  check_extent(result, name);
  if (warnings) {
    for (const std::string& w : soup.warnings) warnings->push_back(name + ": " + w);
    for (const std::string& w : report.warnings) warnings->push_back(name + ": " + w);
  }
  return result;
}

}  // namespace

mesh::SurfaceMesh load_mesh(const std::string& path, std::vector<std::string>* warnings) {
  return mesh_from_soup(read_soup(path), path, warnings);
}

mesh::SurfaceMesh load_mesh_from_memory(const std::uint8_t* data, size_t size, const std::string& name_hint,
                                        std::vector<std::string>* warnings) {
  const Format format = detect_format(name_hint, data, size);
  return mesh_from_soup(read_soup_from_memory(data, size, format, name_hint), name_hint, warnings);
}

PolygonSoup soup_from_mesh(const mesh::SurfaceMesh& mesh) {
  PolygonSoup soup;
  std::vector<std::uint32_t> index(mesh.vertices_size(), 0);
  soup.points.reserve(mesh.n_vertices());
  for (mesh::Vertex v : mesh.vertices()) {
    index[v.idx] = static_cast<std::uint32_t>(soup.points.size());
    const Point& p = mesh.position(v);
    soup.points.push_back({p.x, p.y, p.z});
  }
  soup.triangles.reserve(mesh.n_faces());
  for (mesh::Face f : mesh.faces()) {
    mesh::Vertex v[3];
    mesh.face_vertices(f, v);
    soup.triangles.push_back({index[v[0].idx], index[v[1].idx], index[v[2].idx]});
  }
  return soup;
}

void save_mesh(const mesh::SurfaceMesh& mesh, const std::string& path) {
  write_soup(path, soup_from_mesh(mesh), format_from_path(path));
}

std::vector<std::uint8_t> save_mesh_to_memory(const mesh::SurfaceMesh& mesh, Format format) {
  return write_soup_to_memory(soup_from_mesh(mesh), format);
}

}  // namespace adasculpt::io
