// PLY reader (ascii, binary_little_endian, binary_big_endian) and binary
// little-endian PLY writer.
//
// The header fully describes the data layout, so the reader first parses and
// validates the header (including a check that the declared counts can fit in
// the remaining bytes), then walks every element in file order, keeping the
// vertex positions and the face index lists and skipping everything else.

#include <cmath>
#include <cstring>

#include "io/io_common.h"
#include "io/polygon_triangulation.h"

namespace adasculpt::io::detail {
namespace {

enum class Type : uint8_t { i8, u8, i16, u16, i32, u32, f32, f64 };
enum class Encoding { ascii, binary_le, binary_be };

bool parse_type(std::string_view s, Type& t) {
  static const struct {
    const char* name;
    Type type;
  } kNames[] = {{"char", Type::i8},    {"int8", Type::i8},     {"uchar", Type::u8},
                {"uint8", Type::u8},   {"short", Type::i16},   {"int16", Type::i16},
                {"ushort", Type::u16}, {"uint16", Type::u16},  {"int", Type::i32},
                {"int32", Type::i32},  {"uint", Type::u32},    {"uint32", Type::u32},
                {"float", Type::f32},  {"float32", Type::f32}, {"double", Type::f64},
                {"float64", Type::f64}};
  for (const auto& n : kNames)
    if (s == n.name) {
      t = n.type;
      return true;
    }
  return false;
}
size_t type_size(Type t) {
  switch (t) {
    case Type::i8: case Type::u8: return 1;
    case Type::i16: case Type::u16: return 2;
    case Type::i32: case Type::u32: case Type::f32: return 4;
    case Type::f64: return 8;
  }
  return 0;
}
bool is_integer(Type t) { return t != Type::f32 && t != Type::f64; }

struct Property {
  std::string name;
  Type type = Type::f32;  // item type for lists
  bool is_list = false;
  Type count_type = Type::u8;
};

struct Element {
  std::string name;
  uint64_t count = 0;
  size_t line = 0;  // header line, for errors about the declaration
  std::vector<Property> props;
};

struct Header {
  Encoding encoding = Encoding::ascii;
  std::vector<Element> elements;
  size_t data_offset = 0;
  size_t data_line = 0;
};

Header parse_header(const char* data, size_t size, const std::string& name) {
  TextCursor c(data, data + size);
  if (c.token() != "ply") fail(name, at_line(1), "expected 'ply' magic");
  c.next_line();
  Header h;
  bool have_format = false;
  for (;;) {
    if (c.at_end()) fail(name, at_line(c.line()), "unexpected end of file: missing 'end_header'");
    const size_t line = c.line();
    std::string_view kw = c.token();
    if (kw == "end_header") {
      c.next_line();
      h.data_offset = size_t(c.pos() - data);
      h.data_line = c.line();
      break;
    }
    if (kw.empty() || kw == "comment" || kw == "obj_info") {
      // free text
    } else if (kw == "format") {
      std::string_view f = c.token();
      if (f == "ascii") h.encoding = Encoding::ascii;
      else if (f == "binary_little_endian") h.encoding = Encoding::binary_le;
      else if (f == "binary_big_endian") h.encoding = Encoding::binary_be;
      else fail(name, at_line(line), "unsupported PLY format " + quote(f));
      have_format = true;
    } else if (kw == "element") {
      Element e;
      e.name = std::string(c.token());
      e.line = line;
      if (e.name.empty() || c.parse_int(e.count) != Num::ok)
        fail(name, at_line(line), "malformed element declaration");
      h.elements.push_back(std::move(e));
    } else if (kw == "property") {
      if (h.elements.empty()) fail(name, at_line(line), "property before any element");
      Property p;
      std::string_view t = c.token();
      if (t == "list") {
        p.is_list = true;
        std::string_view ct = c.token();
        if (!parse_type(ct, p.count_type))
          fail(name, at_line(line), "unknown property type " + quote(ct));
        if (!is_integer(p.count_type))
          fail(name, at_line(line), "list length type must be an integer type, found " + quote(ct));
        t = c.token();
      }
      if (!parse_type(t, p.type)) fail(name, at_line(line), "unknown property type " + quote(t));
      p.name = std::string(c.token());
      if (p.name.empty()) fail(name, at_line(line), "property without a name");
      h.elements.back().props.push_back(std::move(p));
    } else {
      fail(name, at_line(line), "unknown PLY header keyword " + quote(kw));
    }
    c.next_line();
  }
  if (!have_format) fail(name, at_line(2), "missing 'format' line");
  return h;
}

// Everything the data walk needs to know about which properties matter.
struct Roles {
  int vertex = -1, face = -1;  // element indices
  int xyz[3] = {-1, -1, -1};   // property indices in the vertex element
  int indices = -1;            // list property index in the face element
};

Roles find_roles(const Header& h, const std::string& name) {
  Roles r;
  for (size_t i = 0; i < h.elements.size(); ++i) {
    const Element& e = h.elements[i];
    if (e.name == "vertex" && r.vertex < 0) r.vertex = int(i);
    if (e.name == "face" && r.face < 0) r.face = int(i);
  }
  if (r.vertex < 0) fail(name, "", "PLY header declares no 'vertex' element");
  const Element& ve = h.elements[r.vertex];
  if (ve.count > UINT32_MAX)
    fail(name, at_line(ve.line), "too many vertices (" + std::to_string(ve.count) + ")");
  static const char* const kAxes[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    for (size_t p = 0; p < ve.props.size(); ++p)
      if (ve.props[p].name == kAxes[a] && !ve.props[p].is_list) r.xyz[a] = int(p);
    if (r.xyz[a] < 0)
      fail(name, at_line(ve.line), std::string("element 'vertex' has no scalar '") + kAxes[a] + "' property");
  }
  if (r.face >= 0) {
    const Element& fe = h.elements[r.face];
    for (size_t p = 0; p < fe.props.size(); ++p)
      if (fe.props[p].name == "vertex_indices" || fe.props[p].name == "vertex_index") r.indices = int(p);
    if (r.indices < 0 || !fe.props[r.indices].is_list)
      fail(name, at_line(fe.line), "element 'face' has no 'vertex_indices' list property");
    if (!is_integer(fe.props[r.indices].type))
      fail(name, at_line(fe.line), "face vertex indices must have an integer type");
  }
  return r;
}

// Refuse counts that cannot possibly fit before allocating anything. A binary
// entry needs at least its fixed-size properties and list lengths; an ascii
// value needs at least one character and a separator.
void check_counts_fit(const Header& h, size_t size, const std::string& name) {
  const uint64_t avail = size - h.data_offset;
  uint64_t needed = 0;
  for (const Element& e : h.elements) {
    if (e.count == 0) continue;
    if (e.props.empty())
      fail(name, at_line(e.line), "element " + quote(e.name) + " has no properties");
    uint64_t min_entry = 0;
    for (const Property& p : e.props)
      min_entry += h.encoding == Encoding::ascii ? 2 : type_size(p.is_list ? p.count_type : p.type);
    if (e.count > (avail + 1) / min_entry || needed + e.count * min_entry > avail + 1)
      fail(name, at_line(e.line),
           "element " + quote(e.name) + " declares " + std::to_string(e.count) +
               " entries, but only " + std::to_string(avail) + " bytes of data follow");
    needed += e.count * min_entry;
  }
}

uint64_t load_uint(const uint8_t* p, size_t n, bool big) {
  uint64_t v = 0;
  for (size_t i = 0; i < n; ++i) v |= uint64_t(p[big ? n - 1 - i : i]) << (8 * i);
  return v;
}
int64_t as_int(uint64_t u, Type t) {
  switch (t) {
    case Type::i8: return int8_t(uint8_t(u));
    case Type::i16: return int16_t(uint16_t(u));
    case Type::i32: return int32_t(uint32_t(u));
    default: return int64_t(u);  // unsigned types
  }
}
double as_double(uint64_t u, Type t) {
  if (t == Type::f32) {
    uint32_t b = uint32_t(u);
    float f;
    std::memcpy(&f, &b, sizeof f);
    return f;
  }
  if (t == Type::f64) {
    double d;
    std::memcpy(&d, &u, sizeof d);
    return d;
  }
  return double(as_int(u, t));
}

std::string entry_context(const Element& e, uint64_t i) {
  return "element " + quote(e.name) + " (entry " + std::to_string(i) + " of " +
         std::to_string(e.count) + ")";
}

std::string out_of_range(int64_t idx, size_t nv) {
  return "face refers to vertex " + std::to_string(idx) + ", file has " + std::to_string(nv) +
         " vertices";
}

void read_binary(const uint8_t* d, size_t size, const Header& h, const Roles& r, PolygonSoup& soup,
                 const std::string& name) {
  const bool big = h.encoding == Encoding::binary_be;
  const size_t nv = soup.points.size();
  size_t pos = h.data_offset;
  std::vector<uint32_t> poly;
  for (size_t ei = 0; ei < h.elements.size(); ++ei) {
    const Element& e = h.elements[ei];
    const bool is_vertex = int(ei) == r.vertex, is_face = int(ei) == r.face;
    for (uint64_t i = 0; i < e.count; ++i) {
      for (size_t pi = 0; pi < e.props.size(); ++pi) {
        const Property& p = e.props[pi];
        auto need = [&](uint64_t n) {
          if (size - pos < n)
            fail(name, at_offset(pos), "unexpected end of file in " + entry_context(e, i));
        };
        if (!p.is_list) {
          const size_t n = type_size(p.type);
          need(n);
          if (is_vertex) {
            for (int a = 0; a < 3; ++a)
              if (int(pi) == r.xyz[a]) {
                double v = as_double(load_uint(d + pos, n, big), p.type);
                if (!std::isfinite(v))
                  fail(name, at_offset(pos),
                       std::string("non-finite vertex coordinate ") +
                           (std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf") + " in vertex " +
                           std::to_string(i));
                soup.points[i][a] = v;
              }
          }
          pos += n;
          continue;
        }
        const size_t cn = type_size(p.count_type), in = type_size(p.type);
        need(cn);
        const size_t list_pos = pos;
        const int64_t len = as_int(load_uint(d + pos, cn, big), p.count_type);
        pos += cn;
        if (len < 0 || uint64_t(len) > (size - pos) / in)
          fail(name, at_offset(list_pos),
               "list length " + std::to_string(len) + " does not fit in the remaining " +
                   std::to_string(size - pos) + " bytes, in " + entry_context(e, i));
        if (!(is_face && int(pi) == r.indices)) {
          pos += size_t(len) * in;
          continue;
        }
        poly.resize(size_t(len));
        for (int64_t k = 0; k < len; ++k, pos += in) {
          const int64_t idx = as_int(load_uint(d + pos, in, big), p.type);
          if (idx < 0 || uint64_t(idx) >= nv) fail(name, at_offset(pos), out_of_range(idx, nv));
          poly[size_t(k)] = uint32_t(idx);
        }
        std::string problem = polygon_problem(poly.data(), poly.size());
        if (!problem.empty()) fail(name, at_offset(list_pos), problem);
        append_polygon(soup, poly.data(), poly.size());
      }
    }
  }
}

void read_ascii(const char* data, size_t size, const Header& h, const Roles& r, PolygonSoup& soup,
                const std::string& name) {
  TextCursor c(data + h.data_offset, data + size, h.data_line);
  const size_t nv = soup.points.size();
  std::vector<uint32_t> poly;
  for (size_t ei = 0; ei < h.elements.size(); ++ei) {
    const Element& e = h.elements[ei];
    const bool is_vertex = int(ei) == r.vertex, is_face = int(ei) == r.face;
    for (uint64_t i = 0; i < e.count; ++i) {
      auto next_value = [&]() {
        c.skip_space();
        if (c.at_end())
          fail(name, at_line(c.line()), "unexpected end of file in " + entry_context(e, i));
      };
      for (size_t pi = 0; pi < e.props.size(); ++pi) {
        const Property& p = e.props[pi];
        next_value();
        if (!p.is_list) {
          int axis = -1;
          if (is_vertex)
            for (int a = 0; a < 3; ++a)
              if (int(pi) == r.xyz[a]) axis = a;
          if (axis >= 0)
            read_number(c, soup.points[i][axis], name, false, false, "missing vertex coordinate");
          else
            c.token();  // value of a property nobody needs
          continue;
        }
        const size_t line = c.line();
        uint64_t len = 0;
        if (c.parse_int(len) != Num::ok)
          fail(name, at_line(line), "malformed list length " + quote(c.peek_token()));
        if (len > c.remaining() / 2 + 1)
          fail(name, at_line(line),
               "list length " + std::to_string(len) + " does not fit in the remaining " +
                   std::to_string(c.remaining()) + " bytes");
        const bool keep = is_face && int(pi) == r.indices;
        if (keep) poly.resize(len);
        for (uint64_t k = 0; k < len; ++k) {
          next_value();
          if (!keep) {
            c.token();
            continue;
          }
          int64_t idx = 0;
          if (c.parse_int(idx) != Num::ok)
            fail(name, at_line(c.line()), "malformed vertex index " + quote(c.peek_token()));
          if (idx < 0 || uint64_t(idx) >= nv) fail(name, at_line(c.line()), out_of_range(idx, nv));
          poly[k] = uint32_t(idx);
        }
        if (!keep) continue;
        std::string problem = polygon_problem(poly.data(), poly.size());
        if (!problem.empty()) fail(name, at_line(line), problem);
        append_polygon(soup, poly.data(), poly.size());
      }
    }
  }
}

void store_le(std::string& out, uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
}

}  // namespace

bool looks_like_ply(const char* data, size_t size) {
  return size >= 4 && std::memcmp(data, "ply", 3) == 0 && (data[3] == '\n' || data[3] == '\r');
}

PolygonSoup read_ply(const uint8_t* bytes, size_t size, const std::string& name) {
  if (size == 0) fail(name, "", "empty file");
  const char* data = reinterpret_cast<const char*>(bytes);
  Header h = parse_header(data, size, name);
  Roles roles = find_roles(h, name);
  check_counts_fit(h, size, name);

  PolygonSoup soup;
  soup.points.resize(h.elements[roles.vertex].count);
  if (roles.face >= 0) soup.triangles.reserve(h.elements[roles.face].count);
  if (h.encoding == Encoding::ascii)
    read_ascii(data, size, h, roles, soup, name);
  else
    read_binary(bytes, size, h, roles, soup, name);
  require_faces(soup, name);
  return soup;
}

void write_ply(const PolygonSoup& soup, std::string& out) {
  if (soup.points.size() > INT32_MAX)
    throw IoError("cannot write PLY: more than 2^31-1 points do not fit 'int' indices");
  out += "ply\nformat binary_little_endian 1.0\ncomment written by adasculpt\nelement vertex ";
  append_uint(out, soup.points.size());
  // Doubles, so that writing never loses precision.
  out += "\nproperty double x\nproperty double y\nproperty double z\nelement face ";
  append_uint(out, soup.triangles.size());
  out += "\nproperty list uchar int vertex_indices\nend_header\n";
  out.reserve(out.size() + soup.points.size() * 24 + soup.triangles.size() * 13);
  for (const auto& p : soup.points)
    for (double v : p) {
      uint64_t bits;
      std::memcpy(&bits, &v, sizeof bits);
      store_le(out, bits, 8);
    }
  for (const auto& t : soup.triangles) {
    out += '\3';
    for (uint32_t v : t) store_le(out, v, 4);
  }
}

}  // namespace adasculpt::io::detail
