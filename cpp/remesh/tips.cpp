// Sharp tips of the reference (issue 17's Hausdorff target): with features off, no sizing keeps
// a vertex on the tip of a spike, and the remesh cuts it.
#include <cmath>

#include <glm/geometric.hpp>

#include "geometry/portable_math.h"
#include "remesh/remesher_impl.h"

namespace adasculpt::remesh {

namespace {
constexpr double kTipDeficit = M_PI / 2;  // a cube's corner
constexpr double kTipHeightTolerances = 2.0;
}  // namespace

// A tip sharper than a cube's corner (angle deficit over pi / 2; features off: with features on
// its sharp edges make it a corner already): no sizing keeps a vertex on it, and a mesh without one
// cuts it by its edge length over the tangent of the tip's half angle (blob.off at epsilon 1 %: a
// three-sided spike 2.8 % of the diagonal from the output). It becomes a corner: never moved or
// removed. Decided again at every reference (a tip may have been sculpted flat). A gentler rule
// (the vertex's height over its ring) pinned vertices of a coarse CAD plate's rims and left
// 13-degree triangles there; a sizing term around such tips instead did not keep vertices on them.
void Remesher::Impl::mark_reference_tips() {
  const double tolerance = surface_tolerance();
  for (Vertex v : mesh.vertices()) {
    if (mesh.is_boundary(v)) continue;
    const Point& p = mesh.position(v);
    double angles = 0;
    bool on_line = false;
    Vec3 normal(0.0), centre(0.0);
    int n = 0;
    for (Halfedge h : mesh.halfedges(v)) {
      on_line = on_line || is_feature(mesh.edge(h));
      const Vec3 a = mesh.position(mesh.to_vertex(h)) - p;
      const Vec3 b = mesh.position(mesh.to_vertex(mesh.next(h))) - p;
      angles += portable::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
      normal += glm::cross(a, b);
      centre += a;
      ++n;
    }
    if (on_line) continue;
    // Only a tip that stands out of its ring by more than the target (2 tolerances) can be cut
    // by more: the dragon's scan has 313 vertices this sharp, all tiny, and pinning them left
    // 10.7-degree triangles at the defaults.
    const double length = glm::length(normal);
    const bool tall = n > 0 && length > 0 &&
                      std::abs(glm::dot(normal / length, centre / double(n))) > kTipHeightTolerances * tolerance;
    vclass[v] = tall && 2 * M_PI - angles > kTipDeficit ? kCorner : kFree;
  }
}

}  // namespace adasculpt::remesh
