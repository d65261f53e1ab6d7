#include "remesh/length_spec.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace adasculpt::remesh {

LengthSpec parse_length_spec(const std::string& text, const std::string& what) {
  std::string number = text;
  LengthSpec s;
  s.percent = !number.empty() && number.back() == '%';
  if (s.percent) number.pop_back();
  const char* begin = number.c_str();
  char* end = nullptr;
  s.value = std::strtod(begin, &end);
  if (number.empty() || end != begin + number.size() || !std::isfinite(s.value))
    throw std::invalid_argument(what + " must be a number, optionally with a % suffix (got '" + text + "')");
  return s;
}

double parse_length(const std::string& text, double diagonal, const std::string& what) {
  return parse_length_spec(text, what).resolve(diagonal);
}

std::string percent_text(double percent) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g%%", percent);
  return buf;
}

}  // namespace adasculpt::remesh
