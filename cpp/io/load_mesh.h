#pragma once
// The glue between files and meshes: read a soup, build the halfedge mesh, and turn the
// builder's topology errors into IoErrors that name the file, so callers (CLI, browser)
// handle exactly one exception type for "this file cannot be used".
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "io/mesh_io.h"
#include "io/polygon_soup.h"
#include "mesh/surface_mesh.h"

namespace adasculpt::io {

// Throws IoError ("path: what"). Repairs (split non-manifold vertices, welded STL
// vertices, ...) are appended to *warnings, each prefixed with the path.
mesh::SurfaceMesh load_mesh(const std::string& path, std::vector<std::string>* warnings = nullptr);
// The format is taken from name_hint's extension when it has a known one, else sniffed.
mesh::SurfaceMesh load_mesh_from_memory(const std::uint8_t* data, size_t size, const std::string& name_hint,
                                        std::vector<std::string>* warnings = nullptr);

// Format from the extension of path.
void save_mesh(const mesh::SurfaceMesh& mesh, const std::string& path);
std::vector<std::uint8_t> save_mesh_to_memory(const mesh::SurfaceMesh& mesh, Format format);

// Live vertices renumbered 0..n-1 in slot order, live faces in slot order.
PolygonSoup soup_from_mesh(const mesh::SurfaceMesh& mesh);

}  // namespace adasculpt::io
