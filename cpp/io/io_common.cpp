#include "io/io_common.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace adasculpt::io::detail {

void fail(const std::string& name, const std::string& where, const std::string& what) {
  std::string msg;
  for (const std::string* part : {&name, &where, &what}) {
    if (part->empty()) continue;
    if (!msg.empty()) msg += ": ";
    msg += *part;
  }
  throw IoError(msg);
}

std::string at_line(size_t line) { return "line " + std::to_string(line); }
std::string at_offset(size_t offset) { return "byte offset " + std::to_string(offset); }

std::string quote(std::string_view token) {
  constexpr size_t kMax = 32;
  std::string s = "'";
  for (size_t i = 0; i < token.size() && i < kMax; ++i) {
    unsigned char c = static_cast<unsigned char>(token[i]);
    if (c >= 0x20 && c < 0x7f) {
      s += static_cast<char>(c);
    } else {
      static const char* hex = "0123456789abcdef";
      s += "\\x";
      s += hex[c >> 4];
      s += hex[c & 15];
    }
  }
  if (token.size() > kMax) s += "...";
  return s + "'";
}

std::string polygon_problem(const uint32_t* idx, size_t n, uint32_t index_base) {
  if (n < 3)
    return "face has " + std::to_string(n) + " vertices, at least 3 needed";
  // Quadratic scan is cheapest for the usual triangles and quads; sort only big polygons.
  if (n <= 32) {
    for (size_t i = 0; i < n; ++i)
      for (size_t j = i + 1; j < n; ++j)
        if (idx[i] == idx[j])
          return "face repeats vertex " + std::to_string(uint64_t(idx[i]) + index_base) + " (degenerate)";
    return {};
  }
  std::vector<uint32_t> sorted(idx, idx + n);
  std::sort(sorted.begin(), sorted.end());
  auto dup = std::adjacent_find(sorted.begin(), sorted.end());
  if (dup != sorted.end())
    return "face repeats vertex " + std::to_string(uint64_t(*dup) + index_base) + " (degenerate)";
  return {};
}

void read_number(TextCursor& c, double& out, const std::string& name, bool multiline,
                 bool allow_nonfinite, const char* missing_what) {
  if (multiline) c.skip_space();
  const size_t line = c.line();
  switch (c.parse_double(out)) {
    case Num::ok:
      if (!allow_nonfinite && !std::isfinite(out))
        fail(name, at_line(line), std::string("non-finite vertex coordinate ") +
                                          (std::isnan(out) ? "nan" : out > 0 ? "inf" : "-inf"));
      return;
    case Num::missing:
      if (c.at_end()) fail(name, at_line(line), std::string("unexpected end of file: ") + missing_what);
      fail(name, at_line(line), missing_what);
    case Num::malformed:
      fail(name, at_line(line), "malformed number " + quote(c.peek_token()));
    case Num::out_of_range:
      fail(name, at_line(line), "number " + quote(c.peek_token()) + " is out of the range of a double");
  }
}

void require_faces(const PolygonSoup& soup, const std::string& name) {
  if (soup.triangles.empty())
    fail(name, "", "no faces (file has " + std::to_string(soup.points.size()) + " vertices)");
}

void check_writable(const PolygonSoup& soup) {
  const size_t np = soup.points.size();
  for (size_t i = 0; i < np; ++i)
    for (double c : soup.points[i])
      if (!std::isfinite(c))
        throw IoError("cannot write: point " + std::to_string(i) + " has a non-finite coordinate");
  for (size_t t = 0; t < soup.triangles.size(); ++t)
    for (uint32_t v : soup.triangles[t])
      if (v >= np)
        throw IoError("cannot write: triangle " + std::to_string(t) + " refers to point " +
                      std::to_string(v) + ", soup has " + std::to_string(np) + " points");
}

void append_double(std::string& out, double v) {
#if ADASCULPT_IO_FP_CHARCONV
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
#else
  // 17 significant digits always read back to the identical double.
  char buf[32];
  int n = std::snprintf(buf, sizeof buf, "%.17g", v);
  out.append(buf, size_t(n));
#endif
}

void append_uint(std::string& out, uint64_t v) {
  char buf[24];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

void append_point_line(std::string& out, const char* prefix, const std::array<double, 3>& p) {
  out += prefix;
  append_double(out, p[0]);
  out += ' ';
  append_double(out, p[1]);
  out += ' ';
  append_double(out, p[2]);
  out += '\n';
}

void append_triangle_line(std::string& out, const char* prefix, const std::array<uint32_t, 3>& t,
                          uint64_t index_base) {
  out += prefix;
  append_uint(out, t[0] + index_base);
  out += ' ';
  append_uint(out, t[1] + index_base);
  out += ' ';
  append_uint(out, t[2] + index_base);
  out += '\n';
}

}  // namespace adasculpt::io::detail
