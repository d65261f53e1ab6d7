#pragma once
// Internal helpers shared by the per-format readers and writers (not part of
// the public interface; include io/mesh_io.h instead).

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "io/mesh_io.h"
#include "io/polygon_soup.h"
#include "io/text_cursor.h"

namespace adasculpt::io::detail {

// Throws IoError "name: where: what", leaving out empty parts.
[[noreturn]] void fail(const std::string& name, const std::string& where, const std::string& what);
std::string at_line(size_t line);
std::string at_offset(size_t offset);

// Quotes a token from the file for an error message; non-printable bytes are
// escaped and long tokens shortened, because the token may be binary junk.
std::string quote(std::string_view token);

// Empty if the polygon is usable, else what is wrong with it (fewer than 3
// vertices, or a repeated index which would make a zero-area triangle).
// index_base is added to indices in the message so they read as in the file
// (1 for OBJ).
std::string polygon_problem(const uint32_t* idx, size_t n, uint32_t index_base = 0);

// Reads one number into `out`, throwing a located IoError for a missing,
// malformed, out-of-range or (unless allow_nonfinite) non-finite value.
// `multiline` lets the number sit on a later line (token-oriented formats).
void read_number(TextCursor& c, double& out, const std::string& name, bool multiline,
                 bool allow_nonfinite, const char* missing_what);
// The three coordinates of a vertex.
inline void read_point(TextCursor& c, std::array<double, 3>& p, const std::string& name,
                       bool multiline) {
  for (double& v : p) read_number(c, v, name, multiline, false, "vertex needs 3 coordinates");
}

// "no faces" is an error for every format: nothing downstream can use such a file.
void require_faces(const PolygonSoup& soup, const std::string& name);

// Writers refuse soups that would produce a file our own readers reject.
void check_writable(const PolygonSoup& soup);

// Text that reads back to the identical double: the shortest such form via
// std::to_chars (exact like %.17g, but shorter), or %.17g where floating-point
// to_chars is unavailable (WebAssembly build).
void append_double(std::string& out, double v);
void append_uint(std::string& out, uint64_t v);
// One text line of a writer: `prefix`, the three values separated by spaces, a newline. Triangle
// corners are written plus `index_base` (OBJ counts from 1, OFF from 0).
void append_point_line(std::string& out, const char* prefix, const std::array<double, 3>& p);
void append_triangle_line(std::string& out, const char* prefix, const std::array<uint32_t, 3>& t,
                          uint64_t index_base);

// Per-format entry points; `name` is only used to prefix error messages.
PolygonSoup read_off(const char* data, size_t size, const std::string& name);
PolygonSoup read_obj(const char* data, size_t size, const std::string& name);
PolygonSoup read_stl(const uint8_t* data, size_t size, const std::string& name);
PolygonSoup read_ply(const uint8_t* data, size_t size, const std::string& name);
void write_off(const PolygonSoup& soup, std::string& out);
void write_obj(const PolygonSoup& soup, std::string& out);
void write_stl(const PolygonSoup& soup, std::string& out);
void write_ply(const PolygonSoup& soup, std::string& out);

// Content sniffing for detect_format().
bool looks_like_off(const char* data, size_t size);
bool looks_like_obj(const char* data, size_t size);
bool looks_like_stl(const uint8_t* data, size_t size);
bool looks_like_ply(const char* data, size_t size);

}  // namespace adasculpt::io::detail
