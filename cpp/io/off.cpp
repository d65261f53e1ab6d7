// OFF (Object File Format) reader and writer.
//
// Read line by line rather than token by token: COFF/NOFF append colours or
// normals to vertex lines and many files append a colour to face lines, so
// "first 3 numbers, ignore the rest of the line" handles every variant.

#include <cstring>

#include "io/io_common.h"
#include "io/polygon_triangulation.h"

namespace adasculpt::io::detail {
namespace {

bool all_digits(std::string_view s) {
  for (char ch : s)
    if (ch < '0' || ch > '9') return false;
  return true;
}

// Splits a header keyword such as "OFF", "COFF", "STNOFF" or "OFF490" (ModelNet
// files glue the vertex count to the keyword). Returns the position just past
// "OFF", or npos if the token is not an OFF header.
size_t off_keyword_end(std::string_view tok) {
  size_t k = tok.find("OFF");
  if (k == std::string_view::npos) return k;
  for (char ch : tok.substr(0, k))
    if (!std::strchr("STCN4n", ch)) return std::string_view::npos;
  if (!all_digits(tok.substr(k + 3))) return std::string_view::npos;
  return k + 3;
}

}  // namespace

bool looks_like_off(const char* data, size_t size) {
  TextCursor c(data, data + size);
  c.skip_bom();
  c.skip_empty_lines('#');
  return off_keyword_end(c.token()) != std::string_view::npos;
}

PolygonSoup read_off(const char* data, size_t size, const std::string& name) {
  TextCursor c(data, data + size);
  c.skip_bom();
  c.skip_empty_lines('#');
  if (c.at_end()) fail(name, "", size == 0 ? "empty file" : "file has no content");

  const size_t header_line = c.line();
  const char* tok_begin = c.pos();
  std::string_view head = c.token();
  size_t kw_end = off_keyword_end(head);
  if (kw_end == std::string_view::npos)
    fail(name, at_line(header_line), "expected OFF header, found " + quote(head));
  std::string_view prefix = head.substr(0, kw_end - 3);
  if (prefix.find_first_of("4n") != std::string_view::npos)
    fail(name, at_line(header_line), "only 3D OFF is supported, found " + quote(head));
  // Rewind over digits glued to the keyword so they are read as the vertex count.
  c = TextCursor(tok_begin + kw_end, data + size, header_line);
  if (!c.at_eol('#')) {
    std::string_view next = c.peek_token();
    if (next == "BINARY" || next == "binary")
      fail(name, at_line(header_line), "binary OFF is not supported");
  }
  c.skip_empty_lines('#');

  // Counts line: "V F [E]"; the edge count is meaningless and ignored.
  const size_t counts_line = c.line();
  uint64_t nv = 0, nf = 0;
  for (uint64_t* n : {&nv, &nf}) {
    Num st = c.parse_int(*n);
    if (st == Num::missing)
      fail(name, at_line(counts_line),
           c.at_end() ? "unexpected end of file: expected vertex and face counts"
                      : "expected vertex and face counts");
    if (st != Num::ok)
      fail(name, at_line(counts_line), "malformed count " + quote(c.peek_token()));
  }
  c.next_line();

  // Refuse absurd headers before allocating anything: every vertex line needs at
  // least "0 0 0\n" (6 bytes) and every face line at least 2 (a real face needs
  // 8, but the looser bound lets short bad faces get their own precise error).
  // A tiny file claiming a billion vertices is corrupt, not worth allocating for.
  const uint64_t rest = c.remaining();
  if (nv > rest || nf > rest || nv * 6 + nf * 2 > rest + 1 || nv > UINT32_MAX)
    fail(name, at_line(counts_line),
         "header declares " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
             " faces, but only " + std::to_string(rest) + " bytes follow");

  PolygonSoup soup;
  soup.points.resize(nv);
  soup.triangles.reserve(nf);
  for (uint64_t i = 0; i < nv; ++i) {
    c.skip_empty_lines('#');
    if (c.at_end())
      fail(name, at_line(c.line()),
           "unexpected end of file: expected " + std::to_string(nv) + " vertices, found " +
               std::to_string(i));
    read_point(c, soup.points[i], name, false);
    c.next_line();
  }

  std::vector<uint32_t> poly;
  for (uint64_t f = 0; f < nf; ++f) {
    c.skip_empty_lines('#');
    const size_t line = c.line();
    if (c.at_end())
      fail(name, at_line(line),
           "unexpected end of file: expected " + std::to_string(nf) + " faces, found " +
               std::to_string(f));
    uint64_t k = 0;
    if (c.parse_int(k) != Num::ok)
      fail(name, at_line(line), "malformed face vertex count " + quote(c.peek_token()));
    // Every listed index takes at least 2 bytes; checked before resizing `poly`.
    if (k > c.remaining() / 2 + 1)
      fail(name, at_line(line),
           "face declares " + std::to_string(k) + " vertices, but only " +
               std::to_string(c.remaining()) + " bytes follow");
    poly.resize(k);
    for (uint64_t j = 0; j < k; ++j) {
      uint64_t idx = 0;
      Num st = c.parse_int(idx);
      if (st == Num::missing)
        fail(name, at_line(line),
             "face declares " + std::to_string(k) + " vertices but lists " + std::to_string(j));
      if (st != Num::ok)
        fail(name, at_line(line), "malformed vertex index " + quote(c.peek_token()));
      if (idx >= nv)
        fail(name, at_line(line),
             "face refers to vertex " + std::to_string(idx) + ", file has " + std::to_string(nv) +
                 " vertices");
      poly[j] = static_cast<uint32_t>(idx);
    }
    std::string problem = polygon_problem(poly.data(), poly.size());
    if (!problem.empty()) fail(name, at_line(line), problem);
    append_polygon(soup, poly.data(), poly.size());
    c.next_line();
  }
  require_faces(soup, name);
  return soup;
}

void write_off(const PolygonSoup& soup, std::string& out) {
  out += "OFF\n";
  append_uint(out, soup.points.size());
  out += ' ';
  append_uint(out, soup.triangles.size());
  out += " 0\n";
  for (const auto& p : soup.points) append_point_line(out, "", p);
  for (const auto& t : soup.triangles) append_triangle_line(out, "3 ", t, 0);
}

}  // namespace adasculpt::io::detail
