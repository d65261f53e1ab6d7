#pragma once
// Lengths given by a user: absolute ("0.01") or a percentage of the mesh's bounding-box
// diagonal ("0.05%"), the form the command line and session files share.
#include <string>

namespace adasculpt::remesh {

// Throws std::invalid_argument naming `what` when the text is not a finite number,
// optionally followed by '%'.
double parse_length(const std::string& text, double diagonal, const std::string& what);

// A length as written: absolute, or percent of the bounding-box diagonal.
struct LengthSpec {
  double value = 0;
  bool percent = false;
  double resolve(double diagonal) const { return percent ? value * 0.01 * diagonal : value; }
};
// The one parser of "x%" / "x" (parse_length and session files use it). Throws
// std::invalid_argument naming `what` as parse_length does.
LengthSpec parse_length_spec(const std::string& text, const std::string& what);

// "0.05%": a percentage (6 significant digits) as text parse_length_spec reads.
std::string percent_text(double percent);

}  // namespace adasculpt::remesh
