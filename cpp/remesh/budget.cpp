// The vertex budget of a whole-mesh remesh: how many vertices the sizing field asks for, and the
// limit the split pass stops at, so that no setting and no input can make the remesher run away.
//
// A triangle of side L covers sqrt(3)/4 L^2; a closed triangle mesh has about twice as many faces
// as vertices, so a surface meshed at the target length L holds 2 / (sqrt(3) L^2) vertices per
// unit area. Integrated over the reference (each triangle: its area times the mean of 1/L^2 at its
// corners), that is the estimate. Remeshed edges settle between 4/5 and 4/3 of L, mostly a little
// under L: the shared meshes come out at 1.0-1.6 times the estimate, so a few times the estimate
// is never reached by a remesh that converges, only by one that does not.
//
// The budget also bounds memory: it is the most vertices the mesh holds at any time, and the first
// split pass on a coarse input reaches far more than the result before the collapses thin the mesh
// out (cheese.off at --uniform --length 0.5%: 726k vertices after the first splits, 229k after the
// collapses, 838 MB). Above some 20k vertices the budget is twice the estimate: the first pass
// stops at 431k, the iterations after it finish the refinement (232k vertices at the end) and the
// peak is under 500 MB. Below that the overshoot costs little memory. A needle input's first pass
// goes several times over its estimate: gen/sliver_cylinder at epsilon 0.05 % asks for 2.2k
// vertices and its 48 needle strips would take 10k; the budget (9.9k) cuts the pass short, and
// fix_bad_faces repairs the needles it leaves (flip_relax.cpp).
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
  const double for_output =
      std::min(kBudgetPerEstimate * estimate, kLargeBudgetPerEstimate * estimate + kLargeBudgetSlack);
  const double budget = for_output + kBudgetPerInputVertex * double(mesh.n_vertices()) + double(kBudgetConstant);
  report.vertex_budget = budget < double(opt.max_vertices) ? size_t(budget) : opt.max_vertices;
}

size_t Remesher::Impl::splits_allowed() const {
  if (!whole_mesh || report.vertex_budget == 0) return SIZE_MAX;  // region calls bound themselves
  const size_t n = mesh.n_vertices();
  return n < report.vertex_budget ? report.vertex_budget - n : 0;
}

void Remesher::Impl::reserve_for_splits() {
  const size_t allowed = splits_allowed();
  if (allowed == SIZE_MAX) return;
  // A split adds a vertex, three edges and two faces. Reserved exactly, where growing one push_back
  // at a time doubles the arrays' capacity: up to twice the memory the budget allows.
  mesh.reserve(mesh.vertices_size() + allowed, mesh.edges_size() + 3 * allowed, mesh.faces_size() + 2 * allowed);
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
