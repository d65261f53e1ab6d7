#include "io/load_mesh.h"

#include "mesh/build_from_triangles.h"

namespace adasculpt::io {

namespace {

mesh::SurfaceMesh mesh_from_soup(const PolygonSoup& soup, const std::string& name,
                                 std::vector<std::string>* warnings) {
  mesh::BuildReport report;
  mesh::SurfaceMesh result;
  try {
    result = mesh::build_from_triangles(soup.points, soup.triangles, &report);
  } catch (const mesh::TopologyError& e) {
    throw IoError(name + ": " + e.what());
  }
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
