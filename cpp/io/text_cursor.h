#pragma once
// Hand-written tokenizer and number parser over an in-memory text buffer.
// Readers must be fast (100k triangles well under 100 ms), so numbers are parsed
// with std::from_chars directly from the buffer: no iostreams, no locale, no
// per-token allocation. The cursor tracks the 1-based line number so errors can
// say where they happened.

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>
#include <system_error>

// Floating-point std::from_chars/to_chars exist in libstdc++ >= 11 but not in
// the libc++ shipped with the Emscripten we build WebAssembly with, so a
// strtod/snprintf fallback is used there. Define ADASCULPT_IO_NO_FP_CHARCONV to
// force the fallback (the tests are run that way too).
#if defined(__cpp_lib_to_chars) && !defined(ADASCULPT_IO_NO_FP_CHARCONV)
#define ADASCULPT_IO_FP_CHARCONV 1
#else
#define ADASCULPT_IO_FP_CHARCONV 0
#endif

namespace adasculpt::io::detail {

enum class Num { ok, missing, malformed, out_of_range };

#if !ADASCULPT_IO_FP_CHARCONV
// Clinger's fast path: when the decimal significand fits in 53 bits and the
// power of ten is exact (|e| <= 22), one IEEE multiply or divide gives the
// correctly rounded result. Typical mesh files (6-9 significant digits) take
// this path; everything else goes to strtod, which is exact but slow in musl.
inline bool fast_decimal(const char* s, const char* e, double& out) {
  static const double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                  1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                  1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  const char* q = s;
  const bool neg = q != e && *q == '-';
  if (neg) ++q;
  uint64_t m = 0;
  int digits = 0, exp10 = 0;
  bool any = false;
  for (; q != e && *q >= '0' && *q <= '9'; ++q, any = true) {
    if (m == 0 && *q == '0') continue;
    if (++digits > 19) return false;
    m = m * 10 + uint64_t(*q - '0');
  }
  if (q != e && *q == '.') {
    for (++q; q != e && *q >= '0' && *q <= '9'; ++q, any = true) {
      --exp10;
      if (m == 0 && *q == '0') continue;
      if (++digits > 19) return false;
      m = m * 10 + uint64_t(*q - '0');
    }
  }
  if (!any) return false;
  if (q != e && (*q == 'e' || *q == 'E')) {
    ++q;
    const bool eneg = q != e && *q == '-';
    if (q != e && (*q == '-' || *q == '+')) ++q;
    int x = 0;
    if (q == e) return false;
    for (; q != e && *q >= '0' && *q <= '9'; ++q) {
      if (x > 10000) return false;
      x = x * 10 + (*q - '0');
    }
    exp10 += eneg ? -x : x;
  }
  if (q != e) return false;
  if (m == 0) {
    out = neg ? -0.0 : 0.0;
    return true;
  }
  if (m > (uint64_t(1) << 53) || exp10 < -22 || exp10 > 22) return false;
  double v = double(m);
  v = exp10 < 0 ? v / kPow10[-exp10] : v * kPow10[exp10];
  out = neg ? -v : v;
  return true;
}
#endif

// Parses all of [s, e) as a decimal double (no leading '+', no hex), the
// grammar of std::from_chars with chars_format::general.
inline Num parse_double_chars(const char* s, const char* e, double& out) {
#if ADASCULPT_IO_FP_CHARCONV
  auto r = std::from_chars(s, e, out);
  if (r.ec == std::errc::result_out_of_range) return Num::out_of_range;
  if (r.ec != std::errc() || r.ptr != e) return Num::malformed;
  return Num::ok;
#else
  if (fast_decimal(s, e, out)) return Num::ok;
  const size_t n = size_t(e - s);
  if (n == 0 || *s == '+' || std::memchr(s, 'x', n) || std::memchr(s, 'X', n) || (*s == ' ' || (*s >= '\t' && *s <= '\r')))
    return Num::malformed;
  char small[64];
  std::string big;
  const char* z = small;  // strtod needs a NUL-terminated copy
  if (n < sizeof small) {
    std::memcpy(small, s, n);
    small[n] = '\0';
  } else {
    big.assign(s, n);
    z = big.c_str();
  }
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(z, &end);
  if (end != z + n) return Num::malformed;
  // ERANGE is also reported for subnormal results, which from_chars accepts.
  if (errno == ERANGE && (std::isinf(v) || v == 0)) return Num::out_of_range;
  out = v;
  return Num::ok;
#endif
}

inline bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}
inline bool is_space(char c) { return is_blank(c) || c == '\n'; }

class TextCursor {
 public:
  TextCursor(const char* begin, const char* end, size_t first_line = 1)
      : p_(begin), end_(end), line_(first_line) {}

  bool at_end() const { return p_ == end_; }
  char peek() const { return *p_; }  // only when !at_end()
  char peek_next() const { return end_ - p_ > 1 ? p_[1] : '\0'; }
  const char* pos() const { return p_; }
  size_t line() const { return line_; }
  size_t remaining() const { return size_t(end_ - p_); }
  void advance(size_t n) { p_ += n; }

  // A UTF-8 byte order mark says nothing about the mesh; editors on Windows add it.
  void skip_bom() {
    if (remaining() >= 3 && std::memcmp(p_, "\xEF\xBB\xBF", 3) == 0) p_ += 3;
  }
  // Blanks only: line-oriented formats must not silently run into the next line.
  void skip_blanks() {
    while (p_ != end_ && is_blank(*p_)) ++p_;
  }
  // Whitespace including newlines, for token-oriented formats (ascii STL/PLY data).
  void skip_space() {
    while (p_ != end_ && is_space(*p_)) {
      if (*p_ == '\n') ++line_;
      ++p_;
    }
  }
  // True when nothing but blanks, or a comment starting with `comment`, is left on the line.
  bool at_eol(char comment = '\0') {
    skip_blanks();
    return p_ == end_ || *p_ == '\n' || (comment != '\0' && *p_ == comment);
  }
  void next_line() {
    const void* nl = std::memchr(p_, '\n', remaining());
    if (nl) {
      p_ = static_cast<const char*>(nl) + 1;
      ++line_;
    } else {
      p_ = end_;
    }
  }
  // Skips empty lines and comment lines; leaves the cursor at the first content character.
  void skip_empty_lines(char comment) {
    while (!at_end() && at_eol(comment)) next_line();
  }
  // Next run of non-whitespace on the current line (empty at end of line).
  std::string_view token() {
    skip_blanks();
    const char* s = p_;
    while (p_ != end_ && !is_space(*p_)) ++p_;
    return {s, size_t(p_ - s)};
  }
  // The token at the cursor without consuming it (for error messages).
  std::string_view peek_token() const {
    const char* s = p_;
    while (s != end_ && is_blank(*s)) ++s;
    const char* e = s;
    while (e != end_ && !is_space(*e)) ++e;
    return {s, size_t(e - s)};
  }

  // A whole whitespace-delimited token that must be a finite-or-not double
  // (finiteness is the caller's business so it can word the error).
  Num parse_double(double& out) {
    skip_blanks();
    const char* s = p_;
    const char* e = s;
    while (e != end_ && !is_space(*e)) ++e;
    if (s == e) return Num::missing;
    // from_chars rejects a leading '+', which some exporters write.
    if (*s == '+' && e - s > 1 && s[1] != '-') ++s;
    const Num st = parse_double_chars(s, e, out);
    if (st == Num::ok) p_ = e;
    return st;
  }

  // An integer token. With stop_at_slash the token may end at '/' (OBJ "v/vt/vn").
  template <typename Int>
  Num parse_int(Int& out, bool stop_at_slash = false) {
    skip_blanks();
    if (p_ == end_ || is_space(*p_)) return Num::missing;
    const char* s = p_;
    if (*s == '+' && end_ - s > 1 && s[1] != '-') ++s;
    auto r = std::from_chars(s, end_, out);
    if (r.ec == std::errc::result_out_of_range) return Num::out_of_range;
    if (r.ec != std::errc()) return Num::malformed;
    if (r.ptr != end_ && !is_space(*r.ptr) && !(stop_at_slash && *r.ptr == '/'))
      return Num::malformed;
    p_ = r.ptr;
    return Num::ok;
  }

 private:
  const char* p_;
  const char* end_;
  size_t line_;
};

}  // namespace adasculpt::io::detail
