#pragma once
// Lengths given by a user: absolute ("0.01") or a percentage of the mesh's bounding-box
// diagonal ("0.05%"), the form the command line and session files share.
#include <string>

namespace adasculpt::remesh {

// Throws std::invalid_argument naming `what` when the text is not a finite number,
// optionally followed by '%'.
double parse_length(const std::string& text, double diagonal, const std::string& what);

}  // namespace adasculpt::remesh
