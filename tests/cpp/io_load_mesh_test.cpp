// io::load_mesh*: soup -> mesh glue, error prefixes, warnings and in-memory round trips.
#include <gtest/gtest.h>

#include <string>

#include "io/load_mesh.h"
#include "mesh/primitives.h"

using namespace adasculpt;

namespace {

mesh::SurfaceMesh load_text(const std::string& text, const std::string& name, std::vector<std::string>* warnings) {
  return io::load_mesh_from_memory(reinterpret_cast<const std::uint8_t*>(text.data()), text.size(), name, warnings);
}

}  // namespace

TEST(IoLoadMesh, NonManifoldEdgeBecomesIoErrorNamingTheFile) {
  const std::string fin = "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n";
  try {
    load_text(fin, "fin.off", nullptr);
    FAIL() << "expected IoError";
  } catch (const io::IoError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("fin.off: non-manifold edge", 0), 0u) << e.what();
  }
}

TEST(IoLoadMesh, RepairWarningsArePrefixed) {
  // Two triangles touching at one vertex: split into two vertices, with a warning.
  const std::string bowtie = "OFF\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n-1 0 0\n-1 -1 0\n3 0 1 2\n3 0 3 4\n";
  std::vector<std::string> warnings;
  mesh::SurfaceMesh m = load_text(bowtie, "bowtie.off", &warnings);
  EXPECT_EQ(m.n_vertices(), 6u);
  ASSERT_FALSE(warnings.empty());
  EXPECT_EQ(warnings[0].rfind("bowtie.off: ", 0), 0u) << warnings[0];
}

TEST(IoLoadMesh, ContentIsSniffedWithoutExtension) {
  mesh::SurfaceMesh m = mesh::make_icosphere(1);
  std::vector<std::uint8_t> ply = io::save_mesh_to_memory(m, io::Format::PLY);
  mesh::SurfaceMesh back = io::load_mesh_from_memory(ply.data(), ply.size(), "upload");
  EXPECT_EQ(back.n_vertices(), m.n_vertices());
  EXPECT_EQ(back.n_faces(), m.n_faces());
}

TEST(IoLoadMesh, SoupFromMeshCompactsDeletedSlots) {
  mesh::SurfaceMesh m = mesh::make_icosphere(2);
  m.collapse(mesh::SurfaceMesh::halfedge(mesh::Edge(3), 0));
  io::PolygonSoup soup = io::soup_from_mesh(m);
  EXPECT_EQ(soup.points.size(), m.n_vertices());
  EXPECT_EQ(soup.triangles.size(), m.n_faces());
  for (const auto& t : soup.triangles)
    for (auto i : t) EXPECT_LT(i, soup.points.size());
  for (io::Format f : {io::Format::OFF, io::Format::OBJ, io::Format::STL, io::Format::PLY}) {
    std::vector<std::uint8_t> bytes = io::save_mesh_to_memory(m, f);
    mesh::SurfaceMesh back = io::load_mesh_from_memory(bytes.data(), bytes.size(), "x");
    EXPECT_EQ(back.n_faces(), m.n_faces());
    back.validate();
  }
}
