#pragma once
// Helpers shared by the io_* tests.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "io/mesh_io.h"

namespace adasculpt::io::io_tests {

// Repository root: from the build's compile definition, else derived from this
// file's own path so the tests also run from an ad-hoc command line.
inline std::string source_dir() {
#ifdef ADASCULPT_SOURCE_DIR
  return ADASCULPT_SOURCE_DIR;
#else
  std::string f = __FILE__;
  return f.substr(0, f.rfind("/tests/cpp/"));
#endif
}

inline std::string data_path(const std::string& rel) { return source_dir() + "/tests/data/" + rel; }

inline PolygonSoup read_text(const std::string& text, Format f, const std::string& name = "test") {
  return read_soup_from_memory(reinterpret_cast<const std::uint8_t*>(text.data()), text.size(), f,
                               name);
}
inline PolygonSoup read_bytes(const std::vector<std::uint8_t>& b, Format f,
                              const std::string& name = "test") {
  return read_soup_from_memory(b.data(), b.size(), f, name);
}

// Message of the IoError thrown by fn, or "" (plus a test failure) if none is thrown.
template <typename Fn>
std::string io_error_of(Fn&& fn) {
  try {
    fn();
  } catch (const IoError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw a non-IoError exception: " << e.what();
    return {};
  }
  ADD_FAILURE() << "no IoError thrown";
  return {};
}

inline bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Little-endian / big-endian byte builders for binary test files.
struct Bytes {
  std::vector<std::uint8_t> data;
  bool big = false;
  void raw(const std::string& s) { data.insert(data.end(), s.begin(), s.end()); }
  void uint(std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) data.push_back(std::uint8_t(v >> (8 * (big ? n - 1 - i : i))));
  }
  void f32(float f) {
    std::uint32_t b;
    std::memcpy(&b, &f, 4);
    uint(b, 4);
  }
  void f64(double d) {
    std::uint64_t b;
    std::memcpy(&b, &d, 8);
    uint(b, 8);
  }
};

}  // namespace adasculpt::io::io_tests
