// Wavefront OBJ reader and writer (geometry only: positions and faces).

#include <cstring>

#include "io/io_common.h"
#include "io/polygon_triangulation.h"

namespace adasculpt::io::detail {
namespace {

// Lines that carry no positions or faces but are perfectly normal in OBJ files.
bool ignorable_keyword(std::string_view kw) {
  static const char* const kIgnored[] = {"vt", "vn", "vp", "o", "g", "s", "usemtl", "mtllib",
                                         "l",  "p"};
  for (const char* k : kIgnored)
    if (kw == k) return true;
  return false;
}

bool keyword_is(const TextCursor& c, char k) {
  return c.peek() == k && (c.remaining() == 1 || is_space(c.peek_next()));
}

}  // namespace

bool looks_like_obj(const char* data, size_t size) {
  // Only the start is inspected: a "v " or "f " line among the first lines,
  // with nothing but known keywords or comments before it.
  TextCursor c(data, data + std::min<size_t>(size, 64 * 1024));
  c.skip_bom();
  for (int lines = 0; lines < 1000 && !c.at_end(); ++lines) {
    if (!c.at_eol('#')) {
      if (keyword_is(c, 'v') || keyword_is(c, 'f')) return true;
      if (!ignorable_keyword(c.token())) return false;
    }
    c.next_line();
  }
  return false;
}

PolygonSoup read_obj(const char* data, size_t size, const std::string& name) {
  if (size == 0) fail(name, "", "empty file");
  TextCursor c(data, data + size);
  c.skip_bom();
  PolygonSoup soup;
  std::vector<uint32_t> poly;
  // Positive indices may legally refer to vertices defined later in the file,
  // so they are range-checked once at the end; remember the worst one and where.
  uint64_t max_index = 0;
  size_t max_index_line = 0;
  size_t unknown_lines = 0, first_unknown_line = 0;
  std::string first_unknown;

  while (!c.at_end()) {
    if (c.at_eol('#')) {
      c.next_line();
      continue;
    }
    const size_t line = c.line();
    if (keyword_is(c, 'v')) {
      c.advance(1);
      std::array<double, 3> p;
      read_point(c, p, name, false);  // "v x y z [w | r g b]": extras ignored
      soup.points.push_back(p);
    } else if (keyword_is(c, 'f')) {
      c.advance(1);
      poly.clear();
      while (!c.at_eol('#')) {
        int64_t idx = 0;
        Num st = c.parse_int(idx, true);
        if (st != Num::ok)
          fail(name, at_line(line), "malformed face vertex " + quote(c.peek_token()));
        // Skip "/vt/vn": texture and normal indices are not used.
        while (!c.at_end() && !is_space(c.peek())) c.advance(1);
        const uint64_t nv = soup.points.size();
        uint64_t v;
        if (idx > 0) {
          v = uint64_t(idx) - 1;
          if (v >= UINT32_MAX)
            fail(name, at_line(line), "vertex index " + std::to_string(idx) + " is too large");
          if (v >= max_index) {
            max_index = v + 1;
            max_index_line = line;
          }
        } else if (idx < 0) {
          // Relative index: -1 is the most recently defined vertex.
          if (uint64_t(-(idx + 1)) >= nv)
            fail(name, at_line(line),
                 "relative vertex index " + std::to_string(idx) + " points before the first vertex (" +
                     std::to_string(nv) + " vertices defined so far)");
          v = nv - uint64_t(-(idx + 1)) - 1;
        } else {
          fail(name, at_line(line), "vertex index 0 is invalid (OBJ indices start at 1)");
        }
        poly.push_back(static_cast<uint32_t>(v));
      }
      std::string problem = polygon_problem(poly.data(), poly.size(), 1);
      if (!problem.empty()) fail(name, at_line(line), problem);
      append_polygon(soup, poly.data(), poly.size());
    } else {
      std::string_view kw = c.token();
      if (!ignorable_keyword(kw)) {
        if (unknown_lines++ == 0) {
          first_unknown = quote(kw);
          first_unknown_line = line;
        }
      }
    }
    c.next_line();
  }

  if (max_index > soup.points.size())
    fail(name, at_line(max_index_line),
         "face refers to vertex " + std::to_string(max_index) + ", file has " +
             std::to_string(soup.points.size()) + " vertices");
  if (unknown_lines > 0)
    soup.warnings.push_back("ignored " + std::to_string(unknown_lines) +
                            " OBJ lines with unsupported keywords (first: " + first_unknown +
                            " at line " + std::to_string(first_unknown_line) + ")");
  require_faces(soup, name);
  return soup;
}

void write_obj(const PolygonSoup& soup, std::string& out) {
  out += "# written by adasculpt\n";
  for (const auto& p : soup.points) append_point_line(out, "v ", p);
  for (const auto& t : soup.triangles) append_triangle_line(out, "f ", t, 1);
}

}  // namespace adasculpt::io::detail
