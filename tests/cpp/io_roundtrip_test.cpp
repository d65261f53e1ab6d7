// Write/read round trips: OFF, OBJ and PLY must reproduce every coordinate
// bit for bit; STL stores floats and must reproduce the float-rounded points.

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <random>

#include "io_test_util.h"

namespace adasculpt::io::io_tests {
namespace {

// A soup whose coordinates are hard to print: random full-precision doubles
// plus negative zero, subnormals, extremes and values with long decimal forms.
PolygonSoup tricky_soup() {
  PolygonSoup s;
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> uni(-1000.0, 1000.0);
  const double special[] = {-0.0,
                            0.1,
                            1.0 / 3,
                            std::numeric_limits<double>::denorm_min(),
                            std::numeric_limits<double>::min(),
                            std::numeric_limits<double>::max(),
                            -std::numeric_limits<double>::max(),
                            std::nextafter(1.0, 2.0),
                            123456789012345678.0,
                            -2.5e-300};
  for (double d : special) s.points.push_back({d, -d, 0.5});
  for (int i = 0; i < 300; ++i) s.points.push_back({uni(rng), uni(rng) * 1e-7, uni(rng) * 1e7});
  std::uniform_int_distribution<uint32_t> pick(0, uint32_t(s.points.size() - 1));
  while (s.triangles.size() < 500) {
    uint32_t a = pick(rng), b = pick(rng), c = pick(rng);
    if (a != b && b != c && a != c) s.triangles.push_back({a, b, c});
  }
  return s;
}

void expect_identical(const PolygonSoup& a, const PolygonSoup& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  for (size_t i = 0; i < a.points.size(); ++i)
    for (int k = 0; k < 3; ++k)
      ASSERT_TRUE(same_bits(a.points[i][k], b.points[i][k]))
          << "point " << i << "[" << k << "]: " << a.points[i][k] << " vs " << b.points[i][k];
  EXPECT_EQ(a.triangles, b.triangles);
}

class IoExactRoundTrip : public testing::TestWithParam<Format> {};

TEST_P(IoExactRoundTrip, MemoryAndFile) {
  const PolygonSoup in = tricky_soup();
  const std::vector<std::uint8_t> bytes = write_soup_to_memory(in, GetParam());
  const PolygonSoup mem = read_bytes(bytes, GetParam());
  expect_identical(in, mem);
  EXPECT_TRUE(mem.warnings.empty());

  const char* ext[] = {"off", "obj", "stl", "ply"};
  const std::string path =
      testing::TempDir() + "adasculpt_roundtrip." + ext[static_cast<int>(GetParam())];
  write_soup(path, in, GetParam());
  expect_identical(in, read_soup(path));
  std::remove(path.c_str());
}

std::string format_name(const testing::TestParamInfo<Format>& info) {
  static const char* const kNames[] = {"OFF", "OBJ", "STL", "PLY"};
  return kNames[static_cast<int>(info.param)];
}

INSTANTIATE_TEST_SUITE_P(Io, IoExactRoundTrip, testing::Values(Format::OFF, Format::OBJ, Format::PLY),
                         format_name);

TEST(IoStlRoundTrip, FloatExact) {
  // Points representable in float (STL's precision), on a closed mesh: welding
  // must restore the shared vertices and the triangles must keep their corners.
  PolygonSoup in = read_soup(data_path("meshes/eight.off"));
  for (auto& p : in.points)
    for (double& c : p) c = double(float(c));
  const PolygonSoup out = read_bytes(write_soup_to_memory(in, Format::STL), Format::STL);
  ASSERT_EQ(out.triangles.size(), in.triangles.size());
  EXPECT_EQ(out.points.size(), in.points.size());
  for (size_t t = 0; t < in.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(out.points[out.triangles[t][k]], in.points[in.triangles[t][k]]) << "triangle " << t;
  ASSERT_EQ(out.warnings.size(), 1u);
  EXPECT_EQ(out.warnings[0], "welded " + std::to_string(3 * in.triangles.size() - in.points.size()) +
                                 " coincident STL vertices");

  // Doubles are rounded to the nearest float, no worse.
  const PolygonSoup tricky = tricky_soup();
  PolygonSoup finite;
  finite.points = {{0.1, 1.0 / 3, -2.5e-30}, {1e7 / 3, 0, 0}, {0, 0, 1}};
  finite.triangles = {{0, 1, 2}};
  const PolygonSoup r = read_bytes(write_soup_to_memory(finite, Format::STL), Format::STL);
  for (int k = 0; k < 3; ++k)
    EXPECT_EQ(r.points[r.triangles[0][0]][k], double(float(finite.points[0][k])));
  // ...and values beyond float range are refused rather than written as inf.
  EXPECT_EQ(io_error_of([&] { write_soup_to_memory(tricky, Format::STL); }).rfind("cannot write STL: point ", 0),
            0u);
}

TEST(IoWriteErrors, RejectsInvalidSoups) {
  PolygonSoup s;
  s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  s.triangles = {{0, 1, 3}};
  for (Format f : {Format::OFF, Format::OBJ, Format::STL, Format::PLY})
    EXPECT_EQ(io_error_of([&] { write_soup_to_memory(s, f); }),
              "cannot write: triangle 0 refers to point 3, soup has 3 points");
  s.triangles = {{0, 1, 2}};
  s.points[1][2] = std::nan("");
  EXPECT_EQ(io_error_of([&] { write_soup("/tmp/never_written.off", s, Format::OFF); }),
            "/tmp/never_written.off: cannot write: point 1 has a non-finite coordinate");
  s.points[1][2] = 0;
  EXPECT_EQ(io_error_of([&] { write_soup("/nonexistent/dir/x.off", s, Format::OFF); }),
            "/nonexistent/dir/x.off: cannot open for writing: No such file or directory");
}

}  // namespace
}  // namespace adasculpt::io::io_tests
