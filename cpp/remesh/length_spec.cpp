#include "remesh/length_spec.h"

#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace adasculpt::remesh {

double parse_length(const std::string& text, double diagonal, const std::string& what) {
  std::string number = text;
  bool percent = !number.empty() && number.back() == '%';
  if (percent) number.pop_back();
  const char* begin = number.c_str();
  char* end = nullptr;
  double value = std::strtod(begin, &end);
  if (number.empty() || end != begin + number.size() || !std::isfinite(value))
    throw std::invalid_argument(what + " must be a number, optionally with a % suffix (got '" + text + "')");
  return percent ? value * 0.01 * diagonal : value;
}

}  // namespace adasculpt::remesh
