// The vertex budget of a whole-mesh remesh: how many vertices the sizing field asks for, and the
// limit the split pass stops at, so that no setting and no input can make the remesher run away.
//
// A triangle of side L covers sqrt(3)/4 L^2; a closed triangle mesh has about twice as many faces
// as vertices, so a surface meshed at the target length L holds 2 / (sqrt(3) L^2) vertices per
// unit area. Integrated over the reference (each triangle: its area times the mean of 1/L^2 at its
// corners), that is the estimate. Remeshed edges settle between 4/5 and 4/3 of L, mostly a little
// under L: the shared meshes come out at 1.0-1.6 times the estimate, so a few times the estimate
// is never reached by a remesh that converges, only by one that does not.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "remesh/remesher_impl.h"

namespace adasculpt::remesh {

namespace {
constexpr double kVerticesPerUnitArea = 2.0 / 1.7320508075688772;  // times 1/L^2
}  // namespace

void Remesher::Impl::estimate_vertex_budget() {
  const auto& pts = tree.points();
  double estimate = 0;
  for (const auto& t : tree.triangles()) {
    const double area = 0.5 * glm::length(glm::cross(pts[t[1]] - pts[t[0]], pts[t[2]] - pts[t[0]]));
    double inverse_square = 0;
    for (std::uint32_t i : t) inverse_square += 1.0 / std::max(ref_sizing[i] * ref_sizing[i], 1e-300);
    estimate += area * inverse_square / 3.0;
  }
  estimate *= kVerticesPerUnitArea;
  report.estimated_vertices = estimate;
  const double budget = kBudgetPerEstimate * estimate + kBudgetPerInputVertex * double(mesh.n_vertices()) +
                        double(kBudgetConstant);
  report.vertex_budget = budget < double(opt.max_vertices) ? size_t(budget) : opt.max_vertices;
}

size_t Remesher::Impl::splits_allowed() const {
  if (!whole_mesh || report.vertex_budget == 0) return SIZE_MAX;  // region calls bound themselves
  const size_t n = mesh.n_vertices();
  return n < report.vertex_budget ? report.vertex_budget - n : 0;
}

void Remesher::Impl::note_budget_reached() {
  if (!report.warning.empty()) return;
  char line[320];
  std::snprintf(line, sizeof line,
                "remeshing stopped refining at its limit of %zu vertices (the settings ask for about %.0f): the "
                "result is the valid mesh reached so far, coarser than asked in places; a larger min length or "
                "epsilon asks for fewer vertices",
                report.vertex_budget, report.estimated_vertices);
  report.warning = line;
}

}  // namespace adasculpt::remesh
