#include "geometry/embedded_fan.h"

#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

namespace adasculpt::geometry {

namespace {
// Relative margin of every sign below: far above the rounding of the differences, the
// projection and the 2D cross products (a few 1e-16 each), so each sign is that of the exact
// value for the projection the rounded axes define.
constexpr double kMargin2 = 1e-24;
}  // namespace

bool star_surely_embedded(const Point& centre, const Point* ring, size_t k) {
  if (k < 3 || k > kMaxCertifiedValence) return false;
  Vec3 e[kMaxCertifiedValence];
  Vec3 n(0.0);
  for (size_t i = 0; i < k; ++i) e[i] = ring[i] - centre;
  for (size_t i = 0; i < k; ++i) n += glm::cross(e[i], e[(i + 1) % k]);
  // The shadows in a frame (u, w) across n, with u x w along n: the 2D cross product of two
  // shadows is dot(u x w, a x b), which has the sign of dot(n, a x b). The margins are taken
  // relative to |a| |b| |u| |w|, the size of the terms whose rounding they must exceed.
  const Vec3 u = glm::cross(n, std::abs(n.x) < std::abs(n.y) ? Vec3(1, 0, 0) : Vec3(0, 1, 0));
  const Vec3 w = glm::cross(n, u);
  const double scale2 = kMargin2 * glm::dot(u, u) * glm::dot(w, w);
  if (!(scale2 > 0)) return false;
  double x[kMaxCertifiedValence], y[kMaxCertifiedValence], len2[kMaxCertifiedValence];
  for (size_t i = 0; i < k; ++i) {
    x[i] = glm::dot(e[i], u);
    y[i] = glm::dot(e[i], w);
    len2[i] = glm::dot(e[i], e[i]);
  }
  // The sign of the 2D cross product of shadows i and j: +1 or -1 when sure, 0 when not.
  auto orientation = [&](size_t i, size_t j) {
    const double c = x[i] * y[j] - y[i] * x[j];
    if (!(c * c > scale2 * len2[i] * len2[j])) return 0;
    return c > 0 ? 1 : -1;
  };
  // Every shadow turns counter-clockwise: a sector of the centre's turn between 0 and 180 degrees.
  for (size_t i = 0; i < k; ++i)
    if (orientation(i, (i + 1) % k) != 1) return false;
  // Exactly one turn: the sectors add up to 360 degrees times the number of turns, so with two or
  // more the direction of e[0] (where the first sector starts and the last ends) lies inside or on
  // the side of another sector as well. Each of the others must have it surely outside.
  for (size_t i = 1; i + 1 < k; ++i)
    if (orientation(i, 0) != -1 && orientation(0, i + 1) != -1) return false;
  return true;
}

bool fan_surely_embedded(const mesh::SurfaceMesh& mesh, mesh::Vertex v) {
  Point ring[kMaxCertifiedValence];
  size_t k = 0;
  bool forward = true;  // whether the face of the outgoing halfedge to ring[i] is (v, ring[i], ring[i + 1])
  for (mesh::Halfedge out : mesh.halfedges(v)) {
    if (k == kMaxCertifiedValence || mesh.is_boundary(out)) return false;
    if (k == 0) {
      // The circulator's turn against the faces' one: the first face's third corner is either
      // the next ring vertex or the last.
      const mesh::Vertex third = mesh.to_vertex(mesh.next(out));
      forward = third == mesh.to_vertex(mesh.cw_rotated(out));
      if (!forward && third != mesh.to_vertex(mesh.ccw_rotated(out))) return false;
    }
    ring[k++] = mesh.position(mesh.to_vertex(out));
  }
  if (!forward)
    for (size_t i = 0, j = k - 1; i < j; ++i, --j) std::swap(ring[i], ring[j]);
  return star_surely_embedded(mesh.position(v), ring, k);
}

}  // namespace adasculpt::geometry
