// Reading valid files in every supported format and flavour.

#include <cmath>
#include <filesystem>
#include <map>

#include "io_test_util.h"

namespace adasculpt::io::io_tests {
namespace {

namespace fs = std::filesystem;
using Tri = std::array<uint32_t, 3>;
using Pt = std::array<double, 3>;

// V and F as listed in /work/shared/meshes/README.md.
const std::map<std::string, std::pair<size_t, size_t>> kSharedMeshCounts = {
    {"fandisk.off", {6475, 12946}},    {"horse.off", {48485, 96966}}, {"bunny.off", {34835, 69666}},
    {"hemisphere.off", {1861, 3600}},  {"face.off", {25905, 51712}},  {"rocker_arm.off", {10044, 20088}},
    {"eight.off", {766, 1536}},        {"dragon.off", {50000, 100000}}};

TEST(IoReaders, SharedMeshesHaveReadmeCounts) {
  const fs::path dir = fs::path(source_dir()) / ".." / "shared" / "meshes";
  if (!fs::is_directory(dir)) GTEST_SKIP() << "shared mesh corpus not found at " << dir;
  size_t checked = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".off") continue;
    const std::string name = entry.path().filename().string();
    SCOPED_TRACE(name);
    PolygonSoup s = read_soup(entry.path().string());
    auto it = kSharedMeshCounts.find(name);
    ASSERT_NE(it, kSharedMeshCounts.end()) << name << " is not listed in the README table";
    EXPECT_EQ(s.points.size(), it->second.first);
    EXPECT_EQ(s.triangles.size(), it->second.second);
    EXPECT_TRUE(s.warnings.empty());
    ++checked;
  }
  EXPECT_EQ(checked, kSharedMeshCounts.size());
}

TEST(IoReaders, BundledMeshes) {
  for (const auto& [name, vf] : kSharedMeshCounts) {
    const std::string path = data_path("meshes/" + name);
    if (!fs::exists(path)) continue;  // only the small ones are bundled
    SCOPED_TRACE(name);
    PolygonSoup s = read_soup(path);
    EXPECT_EQ(s.points.size(), vf.first);
    EXPECT_EQ(s.triangles.size(), vf.second);
  }
  EXPECT_TRUE(fs::exists(data_path("meshes/hemisphere.off")));
  EXPECT_TRUE(fs::exists(data_path("meshes/eight.off")));
  EXPECT_TRUE(fs::exists(data_path("meshes/fandisk.off")));
}

TEST(IoReaders, OffVariants) {
  PolygonSoup s = read_soup(data_path("samples/tet_coff.off"));
  ASSERT_EQ(s.points.size(), 4u);
  EXPECT_EQ(s.points[3], (Pt{0, 0, 1}));
  EXPECT_EQ(s.triangles, (std::vector<Tri>{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}));

  // NOFF normals after the position, CRLF line ends, a BOM and a pentagon.
  s = read_text("\xEF\xBB\xBFNOFF\r\n5 1 0\r\n0 0 0 0 0 1\r\n1 0 0 0 0 1\r\n1 1 0 0 0 1\r\n"
                "0.5 1.5 0 0 0 1\r\n0 1 0 0 0 1\r\n5 0 1 2 3 4\r\n",
                Format::OFF);
  EXPECT_EQ(s.points[3], (Pt{0.5, 1.5, 0}));
  EXPECT_EQ(s.triangles, (std::vector<Tri>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}}));

  // ModelNet-style header with the vertex count glued to the keyword.
  s = read_text("OFF3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", Format::OFF);
  EXPECT_EQ(s.triangles.size(), 1u);
  // Exponents, signs and full precision.
  s = read_text("STOFF\n3 1 0\n-1.5e-3 +2 0.1\n1e300 0 4.9406564584124654e-324\n0 -0 1\n3 2 1 0\n",
                Format::OFF);
  EXPECT_EQ(s.points[0], (Pt{-1.5e-3, 2, 0.1}));
  EXPECT_EQ(s.points[1], (Pt{1e300, 0, 4.9406564584124654e-324}));
  EXPECT_TRUE(std::signbit(s.points[2][1]));
}

TEST(IoReaders, ObjForms) {
  PolygonSoup s = read_soup(data_path("samples/cube_mixed_forms.obj"));
  ASSERT_EQ(s.points.size(), 8u);
  ASSERT_EQ(s.triangles.size(), 12u);
  EXPECT_TRUE(s.warnings.empty());
  // Quad "f 1/1/1 4/4/1 3/3/1 2/2/1" fan-triangulated, 0-based.
  EXPECT_EQ(s.triangles[0], (Tri{0, 3, 2}));
  EXPECT_EQ(s.triangles[1], (Tri{0, 2, 1}));
  // "f -6/1/5 -5/2/5 -1/3/5 -2/4/5" with 8 vertices defined: vertices 3 4 8 7.
  EXPECT_EQ(s.triangles[8], (Tri{2, 3, 7}));
  EXPECT_EQ(s.triangles[9], (Tri{2, 7, 6}));

  // Relative indices resolve against the vertices defined so far, not the total.
  s = read_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 0 0 1\nf -4 -1 -3\n", Format::OBJ);
  EXPECT_EQ(s.triangles, (std::vector<Tri>{{0, 1, 2}, {0, 3, 1}}));

  // Hexagon, extra w / colour values on "v", unknown keywords, faces before vertices.
  s = read_text("f 1 2 3 4 5 6\nv 0 0 0 1\nv 1 0 0 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 2 0\nv -1 1 0\n"
                "curv 0 1 1 2\nparm u 0 1\n",
                Format::OBJ);
  EXPECT_EQ(s.triangles.size(), 4u);
  EXPECT_EQ(s.triangles[3], (Tri{0, 4, 5}));
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0], "ignored 2 OBJ lines with unsupported keywords (first: 'curv' at line 8)");
}

// 12 triangles of a unit cube: 36 corners, 8 distinct points.
const char* const kCubeWeldWarning = "welded 28 coincident STL vertices";

std::vector<std::array<Pt, 3>> corners_of(const PolygonSoup& s) {
  std::vector<std::array<Pt, 3>> out;
  for (const Tri& t : s.triangles) out.push_back({s.points[t[0]], s.points[t[1]], s.points[t[2]]});
  return out;
}

TEST(IoReaders, StlAsciiWelds) {
  PolygonSoup s = read_soup(data_path("samples/cube_ascii.stl"));
  EXPECT_EQ(s.points.size(), 8u);
  EXPECT_EQ(s.triangles.size(), 12u);
  EXPECT_EQ(s.warnings, std::vector<std::string>{kCubeWeldWarning});

  // Upper-case keywords, two solids, a polygonal loop fan-triangulated.
  s = read_text("SOLID a\nFACET NORMAL 0 0 1\nOUTER LOOP\nVERTEX 0 0 0\nVERTEX 1 0 0\nVERTEX 1 1 0\n"
                "VERTEX 0 1 0\nENDLOOP\nENDFACET\nENDSOLID a\nsolid b\nfacet normal 0 0 1\nouter loop\n"
                "vertex 0 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\nendsolid b\n",
                Format::STL);
  EXPECT_EQ(s.triangles.size(), 3u);
  EXPECT_EQ(s.points.size(), 5u);
}

std::vector<std::uint8_t> binary_stl(const std::vector<std::array<Pt, 3>>& tris, const std::string& header) {
  Bytes b;
  std::string h = header;
  h.resize(80, ' ');
  b.raw(h);
  b.uint(tris.size(), 4);
  for (const auto& t : tris) {
    for (int i = 0; i < 3; ++i) b.f32(0);
    for (const Pt& p : t)
      for (double c : p) b.f32(float(c));
    b.uint(0, 2);
  }
  return b.data;
}

TEST(IoReaders, StlBinaryWelds) {
  const PolygonSoup ascii = read_soup(data_path("samples/cube_ascii.stl"));
  // A header starting with "solid" must not fool the reader: the size decides.
  for (const char* header : {"binary cube", "solid cube but binary"}) {
    SCOPED_TRACE(header);
    PolygonSoup s = read_bytes(binary_stl(corners_of(ascii), header), Format::STL);
    EXPECT_EQ(s.points.size(), 8u);
    EXPECT_EQ(s.warnings, std::vector<std::string>{kCubeWeldWarning});
    EXPECT_EQ(corners_of(s), corners_of(ascii));
  }
  // Welding is exact: points 1 ulp apart stay separate; a collapsed triangle is dropped.
  const double eps = std::nextafter(1.0f, 2.0f);
  PolygonSoup s = read_bytes(
      binary_stl({{Pt{0, 0, 0}, Pt{1, 0, 0}, Pt{0, 1, 0}}, {Pt{eps, 0, 0}, Pt{0, 1, 0}, Pt{1, 1, 0}},
                  {Pt{0, 0, 0}, Pt{0, 0, 0}, Pt{1, 1, 0}}},
                 "x"),
      Format::STL);
  EXPECT_EQ(s.points.size(), 5u);
  EXPECT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.warnings, (std::vector<std::string>{"welded 1 coincident STL vertices",
                                                  "dropped 1 degenerate STL triangles (two corners coincide)"}));
}

TEST(IoReaders, PlyAsciiWithExtraProperties) {
  PolygonSoup s = read_soup(data_path("samples/tet_extra_props.ply"));
  ASSERT_EQ(s.points.size(), 4u);
  EXPECT_EQ(s.points[3], (Pt{0, 0, 1}));
  EXPECT_EQ(s.triangles, (std::vector<Tri>{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}));
}

// The same tetrahedron in binary PLY, with double coordinates, an int list
// count, uint indices, extra properties and an extra element, in either byte order.
std::vector<std::uint8_t> binary_ply(bool big, const char* index_name) {
  Bytes b;
  b.big = big;
  b.raw(std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
        " 1.0\nelement vertex 4\nproperty double x\nproperty short flags\nproperty double y\n"
        "property double z\nproperty list uchar float uv\nelement edge 1\nproperty int a\n"
        "property int b\nelement face 4\nproperty uchar kind\nproperty list int uint " +
        index_name + "\nend_header\n");
  const double v[4][3] = {{0.1, 0.2, 0.3}, {1.0 / 3, 0, 0}, {0, 1, 1e-310}, {0, 0, 1}};
  for (const auto& p : v) {
    b.f64(p[0]);
    b.uint(7, 2);
    b.f64(p[1]);
    b.f64(p[2]);
    b.uint(2, 1);
    b.f32(0.5f);
    b.f32(0.25f);
  }
  b.uint(0, 4);
  b.uint(1, 4);
  const uint32_t f[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (const auto& t : f) {
    b.uint(9, 1);
    b.uint(3, 4);
    for (uint32_t i : t) b.uint(i, 4);
  }
  return b.data;
}

TEST(IoReaders, PlyBinaryBothEndiannesses) {
  for (bool big : {false, true})
    for (const char* index_name : {"vertex_indices", "vertex_index"}) {
      SCOPED_TRACE(std::string(big ? "big " : "little ") + index_name);
      PolygonSoup s = read_bytes(binary_ply(big, index_name), Format::PLY);
      ASSERT_EQ(s.points.size(), 4u);
      EXPECT_EQ(s.points[0], (Pt{0.1, 0.2, 0.3}));
      EXPECT_EQ(s.points[1], (Pt{1.0 / 3, 0, 0}));
      EXPECT_EQ(s.points[2], (Pt{0, 1, 1e-310}));
      EXPECT_EQ(s.triangles, (std::vector<Tri>{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}));
    }
}

TEST(IoReaders, FormatFromPath) {
  EXPECT_EQ(format_from_path("a/b/Bunny.OFF"), Format::OFF);
  EXPECT_EQ(format_from_path("x.obj"), Format::OBJ);
  EXPECT_EQ(format_from_path("x.Stl"), Format::STL);
  EXPECT_EQ(format_from_path("dir.v2/x.ply"), Format::PLY);
  EXPECT_EQ(io_error_of([] { format_from_path("dir.off/mesh"); }),
            "dir.off/mesh: unknown mesh file extension '' (expected .off, .obj, .stl or .ply)");
  EXPECT_EQ(io_error_of([] { format_from_path("mesh.3ds"); }),
            "mesh.3ds: unknown mesh file extension '3ds' (expected .off, .obj, .stl or .ply)");
}

TEST(IoReaders, DetectFormatByExtensionThenContent) {
  auto detect = [](const std::string& hint, const std::vector<std::uint8_t>& d) {
    return detect_format(hint, d.data(), d.size());
  };
  auto bytes = [](const std::string& s) { return std::vector<std::uint8_t>(s.begin(), s.end()); };
  // The extension wins even when the content says otherwise.
  EXPECT_EQ(detect("m.obj", bytes("OFF\n")), Format::OBJ);
  EXPECT_EQ(detect("", bytes("# c\n\nCOFF\n3 1 0\n")), Format::OFF);
  EXPECT_EQ(detect("m", bytes("ply\r\nformat ascii 1.0\n")), Format::PLY);
  EXPECT_EQ(detect("m.dat", bytes("solid x\nfacet normal 0 0 1\n")), Format::STL);
  EXPECT_EQ(detect("m.dat", binary_stl({{Pt{0, 0, 0}, Pt{1, 0, 0}, Pt{0, 1, 0}}}, "bin")), Format::STL);
  EXPECT_EQ(detect("m.dat", bytes("# exported\nmtllib a.mtl\no thing\nv 1 2 3\n")), Format::OBJ);
  EXPECT_EQ(io_error_of([&] { detect("m.dat", bytes("hello world\n")); }),
            "m.dat: cannot determine the mesh format from the file name or content");
  EXPECT_EQ(io_error_of([&] { detect("", {}); }),
            "cannot determine the mesh format from the file name or content");

  // read_soup sniffs files with an unknown extension.
  const std::string path = testing::TempDir() + "adasculpt_sniff.mesh";
  write_soup(path, read_soup(data_path("samples/tet_coff.off")), Format::PLY);
  EXPECT_EQ(read_soup(path).triangles.size(), 4u);
  fs::remove(path);
}

TEST(IoReaders, MissingFileNamesThePath) {
  const std::string msg = io_error_of([] { read_soup("/nonexistent/dir/m.off"); });
  EXPECT_EQ(msg, "/nonexistent/dir/m.off: cannot open: No such file or directory");
}

}  // namespace
}  // namespace adasculpt::io::io_tests
