// Bad input: every file in tests/data/malformed/ (made by
// scripts/make-malformed-corpus.py) must be refused with a precise message, and
// damaged versions of valid files must never crash, hang or throw anything but
// IoError.

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <set>

#include "io_test_util.h"

namespace adasculpt::io::io_tests {
namespace {

namespace fs = std::filesystem;

// file name -> expected message after the "<path>: " prefix (exact match).
const std::map<std::string, std::string> kExpected = {
    // OFF
    {"off_empty.off", "empty file"},
    {"off_bad_header.off", "line 1: expected OFF header, found 'OFX'"},
    {"off_4d_header.off", "line 1: only 3D OFF is supported, found '4OFF'"},
    {"off_absurd_counts.off", "line 2: header declares 999999999999 vertices and 1 faces, but only 0 bytes follow"},
    {"off_truncated_vertices.off", "line 5: unexpected end of file: expected 4 vertices, found 3"},
    {"off_truncated_faces.off", "line 9: unexpected end of file: expected 4 faces, found 2"},
    {"off_index_out_of_range.off", "line 10: face refers to vertex 7, file has 4 vertices"},
    {"off_negative_index.off", "line 8: malformed vertex index '-1'"},
    {"off_nan_coordinate.off", "line 5: non-finite vertex coordinate nan"},
    {"off_msvc_infinity.off", "line 4: malformed number '1.#INF'"},
    {"off_two_vertex_face.off", "line 9: face has 2 vertices, at least 3 needed"},
    {"off_repeated_index.off", "line 8: face repeats vertex 1 (degenerate)"},
    {"off_no_faces.off", "no faces (file has 4 vertices)"},
    {"off_huge_polygon.off", "line 7: face declares 999999999 vertices, but only 7 bytes follow"},
    {"off_junk.off", "line 1: expected OFF header, found '\\x00\\x01\\x02\\x03\\x04\\x05\\x06\\x07\\x08'"},
    // OBJ
    {"obj_index_out_of_range.obj", "line 6: face refers to vertex 9, file has 4 vertices"},
    {"obj_zero_index.obj", "line 6: vertex index 0 is invalid (OBJ indices start at 1)"},
    {"obj_relative_before_start.obj",
     "line 6: relative vertex index -5 points before the first vertex (4 vertices defined so far)"},
    {"obj_two_vertex_face.obj", "line 6: face has 2 vertices, at least 3 needed"},
    {"obj_missing_coordinate.obj", "line 2: vertex needs 3 coordinates"},
    {"obj_inf_coordinate.obj", "line 3: non-finite vertex coordinate -inf"},
    {"obj_malformed_face.obj", "line 4: malformed face vertex 'x3'"},
    {"obj_repeated_index.obj", "line 4: face repeats vertex 1 (degenerate)"},
    {"obj_no_faces.obj", "no faces (file has 3 vertices)"},
    {"obj_junk.obj", "no faces (file has 0 vertices)"},
    // STL binary
    {"stl_binary_truncated.stl",
     "byte offset 80: binary STL declares 4 triangles, which needs 284 bytes, but the file has 150 bytes"},
    {"stl_binary_absurd_count.stl",
     "byte offset 80: binary STL declares 4294967295 triangles, which needs 214748364834 bytes, but the file "
     "has 284 bytes"},
    {"stl_binary_short.stl",
     "byte offset 50: unexpected end of file in binary STL header (50 bytes, header and triangle count need 84)"},
    {"stl_binary_no_triangles.stl", "no faces (file has 0 vertices)"},
    {"stl_binary_nan.stl", "byte offset 212: non-finite vertex coordinate nan in triangle 2"},
    {"stl_binary_all_degenerate.stl", "no faces (all 1 triangles are degenerate: two corners coincide)"},
    // STL ascii
    {"stl_ascii_truncated.stl", "line 12: unexpected end of file: expected 'endloop'"},
    {"stl_ascii_bad_number.stl", "line 12: malformed number '0,5'"},
    {"stl_ascii_two_vertex_loop.stl", "line 6: facet loop has 2 vertices, at least 3 needed"},
    {"stl_ascii_missing_endloop.stl", "line 7: expected 'endloop', found 'endfacet'"},
    {"stl_ascii_junk_keyword.stl", "line 9: expected 'facet' or 'endsolid', found 'facet_normal'"},
    // PLY
    {"ply_ascii_index_out_of_range.ply", "line 17: face refers to vertex 4, file has 4 vertices"},
    {"ply_ascii_truncated.ply", "line 17: unexpected end of file in element 'face' (entry 1 of 2)"},
    {"ply_ascii_nan.ply", "line 13: non-finite vertex coordinate nan"},
    {"ply_missing_end_header.ply", "line 5: unexpected end of file: missing 'end_header'"},
    {"ply_bad_format.ply", "line 2: unsupported PLY format 'binary_middle_endian'"},
    {"ply_unknown_type.ply", "line 4: unknown property type 'float128'"},
    {"ply_absurd_count.ply", "line 3: element 'vertex' declares 4000000000 entries, but only 40 bytes of data follow"},
    {"ply_no_vertex_indices.ply", "line 7: element 'face' has no 'vertex_indices' list property"},
    {"ply_binary_le_truncated.ply",
     "byte offset 256: list length 3 does not fit in the remaining 5 bytes, in element 'face' (entry 3 of 4)"},
    {"ply_binary_be_index_out_of_range.ply", "byte offset 262: face refers to vertex 4, file has 4 vertices"},
    {"ply_binary_huge_list.ply",
     "byte offset 203: list length 2000000000 does not fit in the remaining 12 bytes, in element 'face' (entry 0 "
     "of 1)"},
    {"ply_binary_inf.ply", "byte offset 189: non-finite vertex coordinate inf in vertex 1"},
    {"ply_binary_two_vertex_face.ply", "byte offset 230: face has 2 vertices, at least 3 needed"},
    {"ply_binary_no_faces.ply", "no faces (file has 4 vertices)"},
    // neither extension nor content identifies a format
    {"unknown_format.bin", "cannot determine the mesh format from the file name or content"},
};

TEST(IoMalformed, CorpusMatchesTable) {
  const fs::path dir = data_path("malformed");
  std::set<std::string> on_disk;
  for (const auto& e : fs::directory_iterator(dir)) on_disk.insert(e.path().filename().string());
  for (const auto& [name, msg] : kExpected) EXPECT_TRUE(on_disk.count(name)) << "missing file " << name;
  for (const std::string& name : on_disk) EXPECT_TRUE(kExpected.count(name)) << "no expectation for " << name;
  EXPECT_GE(on_disk.size(), 20u);
}

TEST(IoMalformed, EachFileFailsWithItsMessage) {
  for (const auto& [name, msg] : kExpected) {
    SCOPED_TRACE(name);
    const std::string path = data_path("malformed/" + name);
    EXPECT_EQ(io_error_of([&] { read_soup(path); }), path + ": " + msg);
  }
}

// Every prefix and many random corruptions of small valid files in each format
// must either read or throw IoError. Run under ASan/UBSan this also proves the
// readers never touch memory outside the buffer.
std::vector<std::pair<std::string, std::vector<std::uint8_t>>> valid_samples() {
  std::vector<std::pair<std::string, std::vector<std::uint8_t>>> out;
  PolygonSoup tet;
  tet.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  tet.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (Format f : {Format::OFF, Format::OBJ, Format::STL, Format::PLY})
    out.push_back({"written." + std::to_string(int(f)), write_soup_to_memory(tet, f)});
  for (const char* s : {"samples/tet_coff.off", "samples/cube_mixed_forms.obj", "samples/cube_ascii.stl",
                        "samples/tet_extra_props.ply"}) {
    std::ifstream in(data_path(s), std::ios::binary);
    out.push_back({s, std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), {})});
  }
  return out;
}

Format format_of(const std::string& name, const std::vector<std::uint8_t>& d) {
  return detect_format(name, d.data(), d.size());
}

TEST(IoMalformed, TruncationsNeverCrash) {
  for (const auto& [name, data] : valid_samples()) {
    SCOPED_TRACE(name);
    const Format f = name.rfind("written.", 0) == 0 ? Format(name.back() - '0') : format_of(name, data);
    ASSERT_NO_THROW(read_bytes(data, f));
    for (size_t n = 0; n < data.size(); ++n) {
      // Copy into an exactly sized buffer so ASan catches any over-read.
      std::vector<std::uint8_t> prefix(data.begin(), data.begin() + n);
      try {
        read_bytes(prefix, f);
      } catch (const IoError&) {
      }
    }
  }
}

TEST(IoMalformed, RandomCorruptionsNeverCrash) {
  std::mt19937 rng(2024);
  const std::uint8_t interesting[] = {0, 0xff, 0x7f, 0x80, '\n', ' ', '-', '9', '/', '.', 'e', '#'};
  for (const auto& [name, data] : valid_samples()) {
    SCOPED_TRACE(name);
    const Format f = name.rfind("written.", 0) == 0 ? Format(name.back() - '0') : format_of(name, data);
    for (int trial = 0; trial < 2000; ++trial) {
      std::vector<std::uint8_t> d = data;
      const int edits = 1 + int(rng() % 4);
      for (int e = 0; e < edits; ++e) {
        const size_t at = rng() % d.size();
        d[at] = (rng() & 1) ? interesting[rng() % sizeof interesting] : std::uint8_t(rng());
      }
      try {
        read_bytes(d, f);
      } catch (const IoError& e) {
        EXPECT_FALSE(std::string(e.what()).empty());
      }
    }
  }
}

}  // namespace
}  // namespace adasculpt::io::io_tests
