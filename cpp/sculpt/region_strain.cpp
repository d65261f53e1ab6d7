#include "sculpt/region_strain.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "geometry/triangle.h"
#include "mesh/flat_walk.h"

namespace adasculpt::sculpt {

namespace {
std::uint16_t valence(const mesh::SurfaceMesh::HalfedgeConnectivity* hc, const mesh::Halfedge* vh, mesh::Vertex v) {
  std::uint16_t n = 0;
  mesh::for_each_outgoing(hc, vh, v, [&](mesh::Halfedge) { ++n; });
  return n;
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
  edge_strain2_.resize(n, 0.0f);
  next_to_new_.resize(n, 0);
  unsettled_.resize(n, 0);
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
    edge_strain2_[v.idx] = 0.0f;
    next_to_new_[v.idx] = 0;
  }
  // Each edge of the region once (from its lower-numbered end): the larger squared strain of
  // its edges per vertex, and whether a neighbour is new (no position last frame).
  for (mesh::Vertex v : region) {
    const bool v_known = known(v);
    const Point& pv = p[v.idx];
    const Vec3& dv = displacement_[v.idx];
    std::uint16_t edges = 0;  // the valence before this frame's iteration, from the same walk
    mesh::for_each_outgoing(hc, vh, v, [&](mesh::Halfedge h) {
      ++edges;
      const mesh::Index n = hc[h.idx].to.idx;
      if (n < v.idx || in_region_[n] != frame_) return;
      if (!v_known || seen_[n] != frame_) {
        next_to_new_[v.idx] = next_to_new_[n] = 1;
        return;
      }
      const Vec3 e = p[n] - pv, de = displacement_[n] - dv;
      const double e2 = glm::dot(e, e);
      if (!(e2 > 0)) return;
      const float s2 = float(glm::dot(de, de) / e2);
      edge_strain2_[v.idx] = std::max(edge_strain2_[v.idx], s2);
      edge_strain2_[n] = std::max(edge_strain2_[n], s2);
    });
    valence_[v.idx] = edges;
  }
  const float threshold2 = float(threshold * threshold);
  front_.clear();
  for (mesh::Vertex v : region) {
    bool active = !known(v) || unsettled_[v.idx] == frame_ || next_to_new_[v.idx];
    if (!active) {
      strain_[v.idx] += std::sqrt(edge_strain2_[v.idx]);
      active = strain_[v.idx] * strain_[v.idx] >= threshold2;
    }
    if (active) {
      strain_[v.idx] = 0.0f;
      scope_stamp_[v.idx] = frame_;
      front_.push_back(v);
    }
  }
  grow_scope(mesh, region, scope);
}

void RegionStrain::grow_scope(const mesh::SurfaceMesh& mesh, const std::vector<mesh::Vertex>& region,
                              std::vector<mesh::Vertex>& scope) {
  const auto* hc = mesh.halfedge_connectivity_data();
  const mesh::Halfedge* vh = mesh.vertex_halfedge_data();
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
    if (scope_stamp_[v.idx] == frame_) scope.push_back(v);
}

void RegionStrain::select_release(const mesh::SurfaceMesh& mesh, const std::vector<mesh::Vertex>& footprint,
                                  double poor_angle_deg, std::vector<mesh::Vertex>& scope) {
  grow(mesh.vertices_size());
  for (mesh::Vertex v : footprint) in_region_[v.idx] = frame_;
  const double s = std::sin(poor_angle_deg * M_PI / 180.0);
  const double poor_sin2 = s * s;
  front_.clear();
  auto activate = [&](mesh::Vertex v) {
    if (in_region_[v.idx] != frame_ || scope_stamp_[v.idx] == frame_) return;
    scope_stamp_[v.idx] = frame_;
    front_.push_back(v);
  };
  // Each face once, from its lowest-numbered corner in the footprint, on the flat arrays (the
  // circulators made this scan 4 ms of a 12k-vertex footprint's release pass, now 2).
  const auto* hc = mesh.halfedge_connectivity_data();
  const mesh::Halfedge* vh = mesh.vertex_halfedge_data();
  const Point* p = mesh.positions().data();
  auto first_in_footprint = [&](mesh::Index v, mesh::Index other) { return other > v || in_region_[other] != frame_; };
  for (mesh::Vertex v : footprint) {
    if (unsettled_[v.idx] == frame_) activate(v);
    std::uint16_t edges = 0;
    mesh::for_each_outgoing(hc, vh, v, [&](mesh::Halfedge h) {
      ++edges;
      if (!hc[h.idx].face.is_valid()) return;
      const mesh::Index n = hc[h.idx].to.idx, m = hc[hc[h.idx].next.idx].to.idx;
      if (!first_in_footprint(v.idx, n) || !first_in_footprint(v.idx, m)) return;
      if (geometry::min_angle_sin2(p[v.idx], p[n], p[m]) < poor_sin2) {
        activate(v);
        activate(mesh::Vertex(n));
        activate(mesh::Vertex(m));
      }
    });
    valence_[v.idx] = edges;
  }
  grow_scope(mesh, footprint, scope);
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
  ++frame_;
  for (mesh::Vertex v : region) {
    position_[v.idx] = mesh.position(v);
    seen_[v.idx] = frame_;
  }
}

}  // namespace adasculpt::sculpt
