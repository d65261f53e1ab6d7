#pragma once
// Little-endian byte writing and reading for the saved state (session_state.h) and the undo log's
// steps (undo_log.h). Values are copied raw: the formats are little-endian, which native x86 and
// wasm both are (session_state.cpp refuses a big-endian host). A reader that runs out of bytes
// throws std::invalid_argument("saved state: truncated"), so a damaged blob never reads past its end.
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace adasculpt::sculpt::byte_io {

[[noreturn]] inline void fail(const std::string& what) { throw std::invalid_argument("saved state: " + what); }

template <class T>
void put(std::vector<std::uint8_t>& out, const T& v) {
  const auto* p = reinterpret_cast<const std::uint8_t*>(&v);
  out.insert(out.end(), p, p + sizeof(T));
}
// A byte string with its u64 length in front.
inline void put_bytes(std::vector<std::uint8_t>& out, const std::vector<std::uint8_t>& b) {
  put(out, std::uint64_t(b.size()));
  out.insert(out.end(), b.begin(), b.end());
}
// A short name with its u16 length in front.
inline void put_name(std::vector<std::uint8_t>& out, const std::string& s) {
  put(out, std::uint16_t(s.size()));
  out.insert(out.end(), s.begin(), s.end());
}

// Reads from a cursor (p, left) that the caller keeps: both advance as values are read.
struct Reader {
  const std::uint8_t*& p;
  size_t& left;
  template <class T>
  T get() {
    if (left < sizeof(T)) fail("truncated");
    T v;
    std::memcpy(&v, p, sizeof(T));
    p += sizeof(T);
    left -= sizeof(T);
    return v;
  }
  std::vector<std::uint8_t> bytes(size_t n) {
    if (n > left) fail("truncated");
    std::vector<std::uint8_t> v(p, p + n);
    p += n;
    left -= n;
    return v;
  }
  std::string name() {
    const size_t n = get<std::uint16_t>();
    const std::vector<std::uint8_t> b = bytes(n);
    return std::string(b.begin(), b.end());
  }
};

}  // namespace adasculpt::sculpt::byte_io
