// Public entry points: format selection, whole-file I/O and dispatch to the
// per-format readers and writers.

#include "io/mesh_io.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "io/io_common.h"
#include "io/polygon_triangulation.h"

namespace adasculpt::io {
namespace {

// Lower-cased extension of the file name part of `path` ("" if none).
std::string extension_of(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
  std::string ext = path.substr(dot + 1);
  for (char& ch : ext)
    if (ch >= 'A' && ch <= 'Z') ch = char(ch - 'A' + 'a');
  return ext;
}

bool format_from_extension(const std::string& ext, Format& f) {
  if (ext == "off") f = Format::OFF;
  else if (ext == "obj") f = Format::OBJ;
  else if (ext == "stl") f = Format::STL;
  else if (ext == "ply") f = Format::PLY;
  else return false;
  return true;
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

std::vector<std::uint8_t> read_whole_file(const std::string& path) {
  std::unique_ptr<std::FILE, FileCloser> f(std::fopen(path.c_str(), "rb"));
  if (!f) detail::fail(path, "", std::string("cannot open: ") + std::strerror(errno));
  std::vector<std::uint8_t> data;
  // Size via seek so the buffer is allocated once; fall back to chunked reads
  // for things that cannot seek (pipes).
  if (std::fseek(f.get(), 0, SEEK_END) == 0) {
    long size = std::ftell(f.get());
    if (size > 0) data.reserve(size_t(size));
    std::rewind(f.get());
  }
  std::uint8_t buf[1 << 16];
  for (;;) {
    size_t n = std::fread(buf, 1, sizeof buf, f.get());
    data.insert(data.end(), buf, buf + n);
    if (n < sizeof buf) break;
  }
  if (std::ferror(f.get())) detail::fail(path, "", std::string("read error: ") + std::strerror(errno));
  return data;
}

}  // namespace

Format format_from_path(const std::string& path) {
  const std::string ext = extension_of(path);
  Format f;
  if (!format_from_extension(ext, f))
    throw IoError(path + ": unknown mesh file extension '" + ext +
                  "' (expected .off, .obj, .stl or .ply)");
  return f;
}

Format detect_format(const std::string& name_hint, const std::uint8_t* data, size_t size) {
  Format f;
  if (format_from_extension(extension_of(name_hint), f)) return f;
  const char* text = reinterpret_cast<const char*>(data);
  if (data != nullptr && size > 0) {
    // Order matters: PLY and OFF have unambiguous magic words; binary STL is
    // recognised by its exact size; OBJ has no magic and is tried last.
    if (detail::looks_like_ply(text, size)) return Format::PLY;
    if (detail::looks_like_off(text, size)) return Format::OFF;
    if (detail::looks_like_stl(data, size)) return Format::STL;
    if (detail::looks_like_obj(text, size)) return Format::OBJ;
  }
  detail::fail(name_hint, "", "cannot determine the mesh format from the file name or content");
}

PolygonSoup read_soup_from_memory(const std::uint8_t* data, size_t size, Format f,
                                  const std::string& name_for_errors) {
  static const std::uint8_t kEmpty[1] = {0};
  if (data == nullptr || size == 0) {
    data = kEmpty;  // readers never dereference past size; avoids null pointer arithmetic
    size = 0;
  }
  const char* text = reinterpret_cast<const char*>(data);
  PolygonSoup soup;
  switch (f) {
    case Format::OFF: soup = detail::read_off(text, size, name_for_errors); break;
    case Format::OBJ: soup = detail::read_obj(text, size, name_for_errors); break;
    case Format::STL: soup = detail::read_stl(data, size, name_for_errors); break;
    case Format::PLY: soup = detail::read_ply(data, size, name_for_errors); break;
    default: detail::fail(name_for_errors, "", "invalid Format value");
  }
  // The readers cut polygons into fans; the non-convex ones are cut again inside their outlines.
  detail::triangulate_concave_polygons(soup);
  return soup;
}

PolygonSoup read_soup(const std::string& path) {
  std::vector<std::uint8_t> data = read_whole_file(path);
  if (data.empty()) detail::fail(path, "", "empty file");
  return read_soup_from_memory(data.data(), data.size(), detect_format(path, data.data(), data.size()),
                               path);
}

std::vector<std::uint8_t> write_soup_to_memory(const PolygonSoup& soup, Format f) {
  detail::check_writable(soup);
  std::string out;
  switch (f) {
    case Format::OFF: detail::write_off(soup, out); break;
    case Format::OBJ: detail::write_obj(soup, out); break;
    case Format::STL: detail::write_stl(soup, out); break;
    case Format::PLY: detail::write_ply(soup, out); break;
  }
  return std::vector<std::uint8_t>(out.begin(), out.end());
}

void write_soup(const std::string& path, const PolygonSoup& soup, Format f) {
  std::vector<std::uint8_t> bytes;
  try {
    bytes = write_soup_to_memory(soup, f);
  } catch (const IoError& e) {
    throw IoError(path + ": " + e.what());
  }
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) detail::fail(path, "", std::string("cannot open for writing: ") + std::strerror(errno));
  errno = 0;
  const size_t written = std::fwrite(bytes.data(), 1, bytes.size(), file);
  const int write_errno = errno;
  // fclose flushes; a full disk often only shows up here.
  if (std::fclose(file) != 0 || written != bytes.size())
    detail::fail(path, "", std::string("write failed: ") + std::strerror(write_errno ? write_errno : errno));
}

}  // namespace adasculpt::io
