#include "sculpt/region_strain.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "mesh/flat_walk.h"

namespace adasculpt::sculpt {

namespace {
std::uint16_t valence(const mesh::SurfaceMesh::HalfedgeConnectivity* hc, const mesh::Halfedge* vh, mesh::Vertex v) {
  std::uint16_t n = 0;
  mesh::for_each_outgoing(hc, vh, v, [&](mesh::Halfedge) { ++n; });
  return n;
}

// How much strain a vertex may take before it is remeshed again, as a fraction of the threshold,
// from the worst triangle around it: all of it when every angle is 30 degrees or more, a quarter
// at 20 degrees and below (linear in the sine between). A 10 % strain turns an angle by up to
// about 6 degrees: a triangle already near the remesher's 25-30 degrees would fall to ~20 before
// its turn came (the held-out pull's worst triangle between frames fell from 27.7 to 18-24).
float strain_allowance(const mesh::SurfaceMesh::HalfedgeConnectivity* hc, const mesh::Halfedge* vh, const Point* p,
                       mesh::Vertex v) {
  constexpr double kSin20 = 0.3420201433256687, kSin30 = 0.5;
  double worst_sin2 = 1.0;  // sin^2 of the smallest angle of the triangles around v
  mesh::for_each_outgoing(hc, vh, v, [&](mesh::Halfedge h) {
    if (!hc[h.idx].face.is_valid()) return;
    const Point& a = p[v.idx];
    const Point& b = p[hc[h.idx].to.idx];
    const Point& c = p[hc[hc[h.idx].next.idx].to.idx];
    const Vec3 ab = b - a, bc = c - b, ca = a - c;
    const double lab = glm::dot(ab, ab), lbc = glm::dot(bc, bc), lca = glm::dot(ca, ca);
    const Vec3 n = glm::cross(ab, -ca);
    const double area2 = glm::dot(n, n);  // (2 area)^2
    // The smallest angle is opposite the shortest edge: sin^2 = (2A)^2 / (product of the others).
    const double others = std::max({lab * lbc, lbc * lca, lca * lab});
    if (others > 0) worst_sin2 = std::min(worst_sin2, area2 / others);
  });
  const double t = (std::sqrt(worst_sin2) - kSin20) / (kSin30 - kSin20);
  return float(std::clamp(t, 0.25, 1.0));
}

}  // namespace

void RegionStrain::reset() {
  // Stamps of older grabs never equal a later frame_: no array needs clearing.
  frame_ += 2;
}

void RegionStrain::grow(size_t n) {
  if (seen_.size() >= n) return;
  seen_.resize(n, 0);
  position_.resize(n, Point(0.0));
  displacement_.resize(n, Vec3(0.0));
  strain_.resize(n, 0.0f);
  scope_stamp_.resize(n, 0);
  unsettled_.resize(n, 0);
  allowance_.resize(n, 1.0f);
  valence_.resize(n, 0);
  in_region_.resize(n, 0);
}

void RegionStrain::select(const mesh::SurfaceMesh& mesh, const std::vector<mesh::Vertex>& region, double threshold,
                          std::vector<mesh::Vertex>& scope) {
  grow(mesh.vertices_size());
  // Flat arrays: this runs on every vertex of a 10k-vertex region every frame.
  const auto* hc = mesh.halfedge_connectivity_data();
  const mesh::Halfedge* vh = mesh.vertex_halfedge_data();
  const Point* p = mesh.positions().data();
  for (mesh::Vertex v : region) {
    in_region_[v.idx] = frame_;
    if (known(v)) displacement_[v.idx] = p[v.idx] - position_[v.idx];
  }
  const float threshold2 = float(threshold * threshold);
  front_.clear();
  for (mesh::Vertex v : region) {
    bool active = !known(v) || unsettled_[v.idx] == frame_;
    if (!active) {
      const Point& pv = p[v.idx];
      const Vec3& dv = displacement_[v.idx];
      double strain2 = 0;  // the largest squared strain of the edges around v
      mesh::for_each_outgoing(hc, vh, v, [&](mesh::Halfedge h) {
        const mesh::Index n = hc[h.idx].to.idx;
        if (in_region_[n] != frame_) return;
        if (seen_[n] != frame_) {  // a vertex added around v since the last frame
          active = true;
          return;
        }
        const Vec3 e = p[n] - pv, de = displacement_[n] - dv;
        const double e2 = glm::dot(e, e), de2 = glm::dot(de, de);
        if (de2 > strain2 * e2) strain2 = e2 > 0 ? de2 / e2 : strain2;
      });
      strain_[v.idx] += float(std::sqrt(strain2));
      const float allowed = allowance_[v.idx] * allowance_[v.idx] * threshold2;
      active = active || strain_[v.idx] * strain_[v.idx] >= allowed;
    }
    if (active) {
      strain_[v.idx] = 0.0f;
      scope_stamp_[v.idx] = frame_;
      front_.push_back(v);
    }
  }
  // The rings around the active vertices, breadth first, within the region.
  for (int ring = 0; ring < kScopeRings; ++ring) {
    next_front_.clear();
    for (mesh::Vertex v : front_)
      mesh::for_each_outgoing(hc, vh, v, [&](mesh::Halfedge h) {
        const mesh::Index n = hc[h.idx].to.idx;
        if (in_region_[n] != frame_ || scope_stamp_[n] == frame_) return;
        scope_stamp_[n] = frame_;
        next_front_.push_back(mesh::Vertex(n));
      });
    front_.swap(next_front_);
  }
  scope.clear();
  for (mesh::Vertex v : region)
    if (scope_stamp_[v.idx] == frame_) {
      scope.push_back(v);
      valence_[v.idx] = valence(hc, vh, v);
    }
}

void RegionStrain::update_region(const mesh::SurfaceMesh& mesh, std::vector<mesh::Vertex>& region,
                                 const std::vector<mesh::Vertex>& scope) {
  region.erase(std::remove_if(region.begin(), region.end(), [&](mesh::Vertex v) { return mesh.is_deleted(v); }),
               region.end());
  grow(mesh.vertices_size());
  // The vertices around which the iteration changed the connectivity (new ones, and those whose
  // valence changed: a split, collapse or flip next to them) stay in the next frame's scope: the
  // remesher is still at work there (a coarsening region collapses only a share of its edges per
  // frame; a flip or split at the scope's held border left triangles that only relaxation mends).
  const auto* hc = mesh.halfedge_connectivity_data();
  const mesh::Halfedge* vh = mesh.vertex_halfedge_data();
  for (mesh::Vertex v : scope) {
    if (in_region_[v.idx] != frame_) {  // added by the remeshing iteration
      in_region_[v.idx] = frame_;
      strain_[v.idx] = 0.0f;  // (the slot may have held a vertex of an undone grab)
      region.push_back(v);
      unsettled_[v.idx] = frame_ + 1;
    } else if (valence(hc, vh, v) != valence_[v.idx]) {
      unsettled_[v.idx] = frame_ + 1;
    }
  }
  const Point* p = mesh.positions().data();
  for (mesh::Vertex v : scope) allowance_[v.idx] = strain_allowance(hc, vh, p, v);
  ++frame_;
  for (mesh::Vertex v : region) {
    position_[v.idx] = mesh.position(v);
    seen_[v.idx] = frame_;
  }
}

}  // namespace adasculpt::sculpt
