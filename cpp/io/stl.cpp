// STL reader (ascii and binary) and binary STL writer.
//
// STL stores every triangle with its own three corners, so the reader welds
// corners back into shared vertices. Welding is exact (bitwise equal
// coordinates): any tolerance would silently change the geometry, and exporters
// write shared corners with identical bits anyway.

#include <cmath>
#include <cstring>

#include "io/io_common.h"

namespace adasculpt::io::detail {
namespace {

uint32_t load_le32(const uint8_t* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}
float load_le_float(const uint8_t* p) {
  uint32_t bits = load_le32(p);
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}
void store_le32(std::string& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
}
void store_le_float(std::string& out, float f) {
  uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  store_le32(out, bits);
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'A' && x <= 'Z') x = char(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = char(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

bool starts_with_solid(const uint8_t* data, size_t size) {
  TextCursor c(reinterpret_cast<const char*>(data), reinterpret_cast<const char*>(data) + size);
  c.skip_space();
  return iequals(c.token(), "solid");
}

bool is_binary_size(const uint8_t* data, size_t size) {
  return size >= 84 && uint64_t(size) == 84 + 50 * uint64_t(load_le32(data + 80));
}

// Open-addressing hash set of point indices, keyed by the exact bits of the
// point. Stores indices into soup.points so no coordinates are duplicated.
class Welder {
 public:
  // expected_points only sizes the table; it grows if the guess was low.
  Welder(PolygonSoup& soup, size_t expected_points) : soup_(soup) {
    size_t cap = 16;
    while (cap < 2 * expected_points) cap *= 2;
    slots_.assign(cap, 0);
    mask_ = cap - 1;
  }
  uint32_t insert(const std::array<double, 3>& p) {
    size_t i = find_slot(p);
    if (slots_[i] != 0) return slots_[i] - 1;
    soup_.points.push_back(p);
    slots_[i] = uint32_t(soup_.points.size());  // 0 marks an empty slot, so store index + 1
    if (2 * soup_.points.size() > slots_.size()) grow();
    return uint32_t(soup_.points.size() - 1);
  }

 private:
  // Slot holding p, or the empty slot where p belongs.
  size_t find_slot(const std::array<double, 3>& p) const {
    uint64_t b[3];
    std::memcpy(b, p.data(), sizeof b);
    uint64_t h = b[0] * 0x9E3779B97F4A7C15ull;
    h = (h ^ (h >> 29) ^ b[1]) * 0xBF58476D1CE4E5B9ull;
    h = (h ^ (h >> 31) ^ b[2]) * 0x94D049BB133111EBull;
    for (size_t i = (h ^ (h >> 32)) & mask_;; i = (i + 1) & mask_) {
      const uint32_t s = slots_[i];
      if (s == 0 || std::memcmp(soup_.points[s - 1].data(), b, sizeof b) == 0) return i;
    }
  }
  void grow() {
    slots_.assign(slots_.size() * 2, 0);
    mask_ = slots_.size() - 1;
    for (size_t k = 0; k < soup_.points.size(); ++k) slots_[find_slot(soup_.points[k])] = uint32_t(k + 1);
  }

  PolygonSoup& soup_;
  std::vector<uint32_t> slots_;
  size_t mask_ = 0;
};

bool same_bits(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0;
}

// Adds a triangle given by coordinates; returns false (and adds nothing) when two
// corners coincide, since such a triangle has no area and no usable normal.
bool add_triangle(Welder& w, PolygonSoup& soup, const std::array<double, 3> (&c)[3]) {
  if (same_bits(c[0], c[1]) || same_bits(c[1], c[2]) || same_bits(c[0], c[2])) return false;
  soup.triangles.push_back({w.insert(c[0]), w.insert(c[1]), w.insert(c[2])});
  return true;
}

void finish(PolygonSoup& soup, size_t corners_kept, size_t degenerate, const std::string& name) {
  // Degenerate facets are common in real STL exports (slivers rounded to float),
  // so they are dropped with a warning instead of rejecting the whole file.
  if (degenerate > 0 && soup.triangles.empty())
    fail(name, "", "no faces (all " + std::to_string(degenerate) +
                       " triangles are degenerate: two corners coincide)");
  require_faces(soup, name);
  if (corners_kept > soup.points.size())
    soup.warnings.push_back("welded " + std::to_string(corners_kept - soup.points.size()) +
                            " coincident STL vertices");
  if (degenerate > 0)
    soup.warnings.push_back("dropped " + std::to_string(degenerate) +
                            " degenerate STL triangles (two corners coincide)");
}

PolygonSoup read_binary(const uint8_t* data, const std::string& name) {
  const uint32_t n = load_le32(data + 80);
  PolygonSoup soup;
  soup.triangles.reserve(n);
  Welder welder(soup, n);  // closed meshes have about n/2 vertices
  size_t degenerate = 0;
  for (uint32_t t = 0; t < n; ++t) {
    const size_t base = 84 + 50 * size_t(t) + 12;  // skip the stored normal: recomputed downstream
    std::array<double, 3> c[3];
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) {
        const size_t off = base + 12 * k + 4 * a;
        float f = load_le_float(data + off);
        if (!std::isfinite(f))
          fail(name, at_offset(off),
               std::string("non-finite vertex coordinate ") +
                   (std::isnan(f) ? "nan" : f > 0 ? "inf" : "-inf") + " in triangle " +
                   std::to_string(t));
        c[k][a] = f;  // float -> double is exact, so welding on double bits is welding on float bits
      }
    if (!add_triangle(welder, soup, c)) ++degenerate;
  }
  finish(soup, 3 * soup.triangles.size(), degenerate, name);
  return soup;
}

PolygonSoup read_ascii(const uint8_t* bytes, size_t size, const std::string& name) {
  const char* data = reinterpret_cast<const char*>(bytes);
  TextCursor c(data, data + size);
  // A facet takes ~250 bytes of text; the welder grows if this guess is low.
  PolygonSoup soup;
  Welder welder(soup, size / 250 + 16);
  size_t degenerate = 0;

  auto next = [&]() {
    c.skip_space();
    return c.token();
  };
  auto expect = [&](const char* word) {
    c.skip_space();
    const size_t line = c.line();
    std::string_view tok = c.token();
    if (tok.empty()) fail(name, at_line(line), std::string("unexpected end of file: expected '") + word + "'");
    if (!iequals(tok, word))
      fail(name, at_line(line), std::string("expected '") + word + "', found " + quote(tok));
  };

  bool in_solid = false;
  std::vector<std::array<double, 3>> loop;
  for (;;) {
    c.skip_space();
    const size_t line = c.line();
    std::string_view tok = next();
    if (tok.empty()) break;  // end of file
    if (iequals(tok, "solid")) {
      if (in_solid) fail(name, at_line(line), "'solid' inside a solid (missing 'endsolid')");
      in_solid = true;
      c.next_line();  // the solid's name is free text
    } else if (iequals(tok, "endsolid")) {
      if (!in_solid) fail(name, at_line(line), "'endsolid' without 'solid'");
      in_solid = false;
      c.next_line();
    } else if (iequals(tok, "facet")) {
      if (!in_solid) fail(name, at_line(line), "'facet' outside a solid");
      expect("normal");
      double ignored;
      for (int a = 0; a < 3; ++a) read_number(c, ignored, name, true, true, "facet normal needs 3 numbers");
      expect("outer");
      expect("loop");
      loop.clear();
      for (;;) {
        c.skip_space();
        std::string_view kw = c.peek_token();
        if (!iequals(kw, "vertex")) break;
        c.token();
        std::array<double, 3> p;
        read_point(c, p, name, true);
        loop.push_back(p);
      }
      const size_t end_line = c.line();
      expect("endloop");
      expect("endfacet");
      if (loop.size() < 3)
        fail(name, at_line(end_line),
             "facet loop has " + std::to_string(loop.size()) + " vertices, at least 3 needed");
      // Some exporters write polygonal loops; fan-triangulate like the other formats.
      for (size_t i = 1; i + 1 < loop.size(); ++i) {
        const std::array<double, 3> tri[3] = {loop[0], loop[i], loop[i + 1]};
        if (!add_triangle(welder, soup, tri)) ++degenerate;
      }
    } else {
      fail(name, at_line(line), "expected 'facet' or 'endsolid', found " + quote(tok));
    }
  }
  if (in_solid) soup.warnings.push_back("ascii STL ends without 'endsolid'");
  finish(soup, 3 * soup.triangles.size(), degenerate, name);
  return soup;
}

}  // namespace

bool looks_like_stl(const uint8_t* data, size_t size) {
  return is_binary_size(data, size) || starts_with_solid(data, size);
}

PolygonSoup read_stl(const uint8_t* data, size_t size, const std::string& name) {
  if (size == 0) fail(name, "", "empty file");
  // Many binary files also begin with "solid" in their 80-byte header, so the
  // exact size 84 + 50 n is the reliable test and is tried first.
  if (is_binary_size(data, size)) return read_binary(data, name);
  if (starts_with_solid(data, size)) return read_ascii(data, size, name);
  if (size < 84)
    fail(name, at_offset(size),
         "unexpected end of file in binary STL header (" + std::to_string(size) +
             " bytes, header and triangle count need 84)");
  const uint32_t n = load_le32(data + 80);
  fail(name, at_offset(80),
       "binary STL declares " + std::to_string(n) + " triangles, which needs " +
           std::to_string(84 + 50 * uint64_t(n)) + " bytes, but the file has " +
           std::to_string(size) + " bytes");
}

void write_stl(const PolygonSoup& soup, std::string& out) {
  // The header must not start with "solid", or other readers take it for ascii.
  std::string header = "binary STL written by adasculpt";
  header.resize(80, ' ');
  out += header;
  if (soup.triangles.size() > UINT32_MAX)
    throw IoError("cannot write STL: more than 2^32-1 triangles");
  store_le32(out, uint32_t(soup.triangles.size()));
  for (size_t t = 0; t < soup.triangles.size(); ++t) {
    float v[3][3];
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) {
        const double d = soup.points[soup.triangles[t][k]][a];
        v[k][a] = static_cast<float>(d);
        if (!std::isfinite(v[k][a]))
          throw IoError("cannot write STL: point " + std::to_string(soup.triangles[t][k]) +
                        " does not fit in a 32-bit float");
      }
    // Normal from the float corners, as a reader would compute it.
    const float e1[3] = {v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2]};
    const float e2[3] = {v[2][0] - v[0][0], v[2][1] - v[0][1], v[2][2] - v[0][2]};
    float nrm[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                    e1[0] * e2[1] - e1[1] * e2[0]};
    const float len = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    for (float& x : nrm) x = (len > 0 && std::isfinite(len)) ? x / len : 0.0f;
    for (float x : nrm) store_le_float(out, x);
    for (auto& corner : v)
      for (float x : corner) store_le_float(out, x);
    out += '\0';  // attribute byte count, unused
    out += '\0';
  }
}

}  // namespace adasculpt::io::detail
