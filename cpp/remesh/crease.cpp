// Creases and sharp tips of a polyhedral reference (issue 17's Hausdorff target at fine epsilon). The
// paper's field comes from vertex curvature, which on a coarse input spreads an input edge's
// dihedral angle theta over its vertices' areas: it asks for edges of about sqrt(6 eps h / theta)
// (h the input edge length), while an output edge of length L crossing the edge misses it by about
// L theta / 4. Where eps << h the curvature's edges are far too long (negative.off, six triangles,
// at eps 0.05 %: Hausdorff 0.34 % of the diagonal). Here each input edge that is longer than the
// field's length and stands out of its facets by more than the tolerance (max(eps, min length /
// 2), surface_tolerance()) asks for L = 4 tolerance / theta beside it, growing by the gradation
// limit with the distance to it. The term is applied per query point (sizing_of_hit), not stored
// at the reference's vertices: interpolated over a coarse input's large flat facets, vertex values
// would refine whole facets instead of the strips along their edges.
#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "geometry/portable_math.h"
#include "geometry/triangle.h"
#include "remesh/remesher_impl.h"

namespace adasculpt::remesh {

namespace {
constexpr float kNoCrease = std::numeric_limits<float>::infinity();
// An edge crossing a crease of angle theta at length L misses it by about L theta / 4.
constexpr double kCreaseMissPerLengthAngle = 0.25;
constexpr double kTipDeficit = M_PI / 2;  // a cube's corner
constexpr double kTipHeightTolerances = 2.0;
constexpr double kVerticesPerUnitArea = 2.0 / 1.7320508075688772;  // as budget.cpp: times 1/L^2
}  // namespace

void Remesher::Impl::measure_reference_creases() {
  ref_edge_crease.clear();
  ref_point_crease.clear();
  crease_vertex_estimate = 0;
  // Only where epsilon sets the tolerance: where the min length does (the defaults: epsilon 0.05 %,
  // min length 0.2 %), edges of about the min length miss a crease by up to half their length, the
  // reach the Hausdorff target allows them, and strips of such edges along every sharp edge of a CAD
  // part with features off cost fandisk 2.3 times the vertices and its mean min angle 50.3 -> 49.3.
  if (!opt.adaptive || clamp_decides_sizing() || !(opt.epsilon >= kToleranceMinLengths * opt.min_length)) return;
  const auto& tris = tree.triangles();
  const auto& pts = tree.points();
  ref_edge_crease.assign(tris.size(), {kNoCrease, kNoCrease, kNoCrease});
  ref_point_crease.assign(pts.size(), kNoCrease);
  auto unit_normal = [&](std::uint32_t ti) {
    const auto& t = tris[ti];
    const Vec3 n = glm::cross(pts[t[1]] - pts[t[0]], pts[t[2]] - pts[t[0]]);
    const double l = glm::length(n);
    return l > 0 ? n / l : Vec3(0.0);
  };
  // Height of triangle ti's third corner over its edge i (from corner i to corner i + 1).
  auto height_over_edge = [&](std::uint32_t ti, int i) {
    const auto& t = tris[ti];
    const Vec3 edge = pts[t[(i + 1) % 3]] - pts[t[i]];
    const double l = glm::length(edge);
    return l > 0 ? glm::length(glm::cross(edge, pts[t[(i + 2) % 3]] - pts[t[i]])) / l : 0.0;
  };
  auto edge_index = [&](std::uint32_t ti, std::uint32_t a, std::uint32_t b) {
    const auto& t = tris[ti];
    for (int i = 0; i < 3; ++i)
      if ((t[i] == a && t[(i + 1) % 3] == b) || (t[i] == b && t[(i + 1) % 3] == a)) return i;
    return 0;
  };
  // The tolerance the Hausdorff target allows (max(eps, min length / 2)), met with the margin of
  // the target's factor 2.
  const double tolerance = surface_tolerance();
  auto is_line = [&](std::uint32_t a, std::uint32_t b) {  // feature lines are followed, not crossed
    for (std::uint32_t k = ref_segment_offset[a]; k < ref_segment_offset[a + 1]; ++k) {
      const auto& s = ref_segments[ref_segment_of_point[k]];
      if (s[0] == b || s[1] == b) return true;
    }
    return false;
  };
  for (std::uint32_t ti = 0; ti < tris.size(); ++ti)
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t other = ref_adjacent[ti][i];
      if (other == UINT32_MAX) continue;
      const std::uint32_t a = tris[ti][i], b = tris[ti][(i + 1) % 3];
      const Vec3 n0 = unit_normal(ti), n1 = unit_normal(other);
      const double theta = portable::atan2(glm::length(glm::cross(n0, n1)), glm::dot(n0, n1));
      if (!(theta > 0)) continue;
      // The crease matters only where it stands out of its two facets by more than the tolerance:
      // by theta x a0 a1 / (a0 + a1) over the chord between their far corners (a0, a1 their heights
      // over the edge). A scan's small facets meet at noisy angles (bunny: a third of its input
      // edges turn by 10 degrees or more) that no output edge can miss by that much.
      // Nor where the input is finer than the field: there the vertex curvature measured it.
      if (glm::length(pts[b] - pts[a]) <= std::min(ref_sizing[a], ref_sizing[b])) continue;
      const double a0 = height_over_edge(ti, i), a1 = height_over_edge(other, edge_index(other, a, b));
      if (!(theta * a0 * a1 > tolerance * (a0 + a1))) continue;
      const double size = std::max(tolerance / (kCreaseMissPerLengthAngle * theta), opt.min_length);
      if (size >= opt.max_length || is_line(a, b)) continue;
      ref_edge_crease[ti][i] = static_cast<float>(size);
      ref_point_crease[a] = std::min(ref_point_crease[a], static_cast<float>(size));
      ref_point_crease[b] = std::min(ref_point_crease[b], static_cast<float>(size));
      // The strip of the edge on this triangle's side (the other side counts on its own): the
      // sizing L + g d over distances d from 0 on holds about length / (g L) vertices per unit
      // area of 1/L^2 density. Only where the strip asks for more than the field already does.
      if (size < std::min(ref_sizing[a], ref_sizing[b]))
        crease_vertex_estimate += kVerticesPerUnitArea * glm::length(pts[b] - pts[a]) / (kGradation * size);
    }
}

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

double Remesher::Impl::crease_sizing(const geometry::TriangleTree::ClosestHit& hit) const {
  if (ref_point_crease.empty()) return std::numeric_limits<double>::infinity();
  const auto& t = tree.triangles()[hit.triangle];
  double size = std::numeric_limits<double>::infinity();
  const auto& pts = tree.points();
  // From the corners: a crease edge of the triangles that share only a corner with this one.
  for (int i = 0; i < 3; ++i)
    if (ref_point_crease[t[i]] != kNoCrease)
      size = std::min(size, ref_point_crease[t[i]] + kGradation * glm::length(hit.point - pts[t[i]]));
  if (size == std::numeric_limits<double>::infinity()) return size;  // no crease at any corner
  // Along this triangle's own crease edges.
  for (int i = 0; i < 3; ++i)
    if (ref_edge_crease[hit.triangle][i] != kNoCrease) {
      const Point q = geometry::closest_point_on_segment(hit.point, pts[t[i]], pts[t[(i + 1) % 3]]);
      size = std::min(size, ref_edge_crease[hit.triangle][i] + kGradation * glm::length(hit.point - q));
    }
  return size;
}

}  // namespace adasculpt::remesh
