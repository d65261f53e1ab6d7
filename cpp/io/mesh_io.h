#pragma once
// Mesh file input/output: OFF, OBJ, STL (ascii + binary) and PLY (ascii + binary).
// Every failure is reported as IoError with a message that names the file and
// the line (text formats) or byte offset (binary formats) of the problem.

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/polygon_soup.h"

namespace adasculpt::io {

enum class Format { OFF, OBJ, STL, PLY };

class IoError : public std::runtime_error {
  using runtime_error::runtime_error;
};  // message says what and where

// By extension, case-insensitive; IoError if unknown.
Format format_from_path(const std::string& path);
// Extension of name_hint if it is a known one, else sniff the content.
Format detect_format(const std::string& name_hint, const std::uint8_t* data, size_t size);
// Reads the whole file; errors are prefixed with the file path.
PolygonSoup read_soup(const std::string& path);
PolygonSoup read_soup_from_memory(const std::uint8_t* data, size_t size, Format f,
                                  const std::string& name_for_errors);
// Throws IoError on failure (including a soup with bad indices or non-finite points).
void write_soup(const std::string& path, const PolygonSoup&, Format f);
std::vector<std::uint8_t> write_soup_to_memory(const PolygonSoup&, Format f);

}  // namespace adasculpt::io
