#include "deform/geodesic.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include <glm/geometric.hpp>

namespace adasculpt::deform {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

double GeodesicWorkspace::distance(Vertex v) const { return reached(v) ? dist_[v.idx] : kInf; }

void GeodesicWorkspace::start(size_t n) {
  if (dist_.size() < n) {
    dist_.resize(n, kInf);
    stamp_.resize(n, 0);
    final_.resize(n, 0);
  }
  if (++run_ == 0) {  // wrapped: stamps from 2^32 runs ago would alias
    std::fill(stamp_.begin(), stamp_.end(), 0);
    run_ = 1;
  }
  order_.clear();
  heap_.clear();
}

double triangle_update(const Point& a, const Point& b, const Point& c, double da, double db) {
  const double edge_a = da + glm::length(c - a), edge_b = db + glm::length(c - b);
  const double fallback = std::min(edge_a, edge_b);
  const Vec3 ab = b - a;
  const double lab = glm::length(ab);
  if (lab <= 0) return fallback;
  // Plane coordinates: A = (0,0), B = (lab,0), C = (cx,cy) with cy >= 0.
  const Vec3 ac = c - a;
  const double cx = glm::dot(ac, ab) / lab;
  const double cy2 = glm::dot(ac, ac) - cx * cx;
  if (cy2 <= 0) return fallback;
  const double cy = std::sqrt(cy2);
  // Virtual source S = (sx, -sy) on the other side of AB.
  const double sx = (da * da - db * db + lab * lab) / (2 * lab);
  const double sy2 = da * da - sx * sx;
  if (sy2 < 0) return fallback;  // |dA - dB| > |AB|: no planar source
  const double sy = std::sqrt(sy2);
  // Where the segment S->C crosses the line AB.
  const double t = sy / (sy + cy);
  const double xcross = sx + t * (cx - sx);
  if (xcross < 0 || xcross > lab) return fallback;
  const double d = std::sqrt((cx - sx) * (cx - sx) + (cy + sy) * (cy + sy));
  return std::min(d, fallback);
}

void geodesic_distance(const SurfaceMesh& mesh, const std::vector<std::pair<Vertex, double>>& seeds,
                       double max_distance, GeodesicWorkspace& ws, bool edges_only, size_t max_vertices) {
  ws.start(mesh.vertices_size());
  auto& dist = ws.dist_;
  auto& stamp = ws.stamp_;
  auto& fin = ws.final_;
  auto& heap = ws.heap_;
  const std::uint32_t run = ws.run_;
  auto cmp = std::greater<std::pair<double, Vertex>>();
  auto relax = [&](Vertex v, double d) {
    if (stamp[v.idx] != run) {
      stamp[v.idx] = run;
      fin[v.idx] = 0;
      dist[v.idx] = kInf;
    }
    if (fin[v.idx] || d >= dist[v.idx]) return;
    dist[v.idx] = d;
    heap.emplace_back(d, v);
    std::push_heap(heap.begin(), heap.end(), cmp);
  };
  for (const auto& [v, d] : seeds)
    if (v.is_valid() && !mesh.is_deleted(v)) relax(v, d);

  while (!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end(), cmp);
    auto [d, v] = heap.back();
    heap.pop_back();
    if (fin[v.idx] || d > dist[v.idx]) continue;  // stale entry
    if (d > max_distance || ws.order_.size() >= max_vertices) break;
    fin[v.idx] = 1;
    ws.order_.push_back(v);
    const Point& pv = mesh.position(v);
    for (mesh::Halfedge h : mesh.halfedges(v)) {
      const Vertex u = mesh.to_vertex(h);
      if (stamp[u.idx] == run && fin[u.idx]) continue;
      double du = d + glm::length(mesh.position(u) - pv);
      if (!edges_only) {
        // The two triangles on either side of edge v-u: third corner w final -> unfold.
        const mesh::Halfedge sides[2] = {h, mesh.opposite(h)};
        for (mesh::Halfedge s : sides) {
          if (mesh.is_boundary(s)) continue;
          const Vertex w = mesh.to_vertex(mesh.next(s));  // third corner of the triangle of s
          if (w == u || w == v || stamp[w.idx] != run || !fin[w.idx]) continue;
          du = std::min(du, triangle_update(pv, mesh.position(w), mesh.position(u), d, dist[w.idx]));
        }
      }
      relax(u, du);
    }
  }
}

}  // namespace adasculpt::deform
