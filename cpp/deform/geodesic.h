#pragma once
// Local geodesic distance from a set of seed vertices, for the region of interest of a grab.
//
// Fast-marching style: vertices are finalised in Dijkstra order, but a vertex's tentative
// distance is also updated from every triangle whose two other corners are final, using the
// planar unfolding of that triangle (a virtual source S with |S-A| = d(A), |S-B| = d(B) on the
// far side of AB; d(C) = |S-C| when the straight path S->C crosses AB, else the edge update).
// Plain Dijkstra on edges measures zig-zag paths and gives star-shaped "circles" on irregular
// meshes; the triangle update makes them round (tests/cpp/deform_geodesic_test.cpp).
//
// The march stops at max_distance, so the work is proportional to the region reached, not to
// the mesh. Distances live in a GeodesicWorkspace that is reused between frames: its arrays grow
// with the mesh but are never cleared in full (a per-run stamp marks the valid entries).
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "mesh/surface_mesh.h"

namespace adasculpt::deform {

using mesh::SurfaceMesh;
using mesh::Vertex;

class GeodesicWorkspace {
 public:
  // Distance of v in the last run; infinity if v was not reached (not within max_distance).
  double distance(Vertex v) const;
  bool reached(Vertex v) const { return v.idx < stamp_.size() && stamp_[v.idx] == run_ && final_[v.idx]; }
  // Vertices reached by the last run, in the order they were finalised (increasing distance).
  const std::vector<Vertex>& order() const { return order_; }

 private:
  friend void geodesic_distance(const SurfaceMesh&, const std::vector<std::pair<Vertex, double>>&, double,
                                GeodesicWorkspace&, bool, size_t);
  void start(size_t n_vertex_slots);
  std::vector<double> dist_;
  std::vector<std::uint32_t> stamp_;  // == run_: dist_ valid; state_ tells tentative or final
  std::vector<std::uint8_t> final_;
  std::vector<Vertex> order_;
  std::vector<std::pair<double, Vertex>> heap_;
  std::uint32_t run_ = 0;
};

// Distances from the seeds (vertex, initial distance) to every vertex within max_distance.
// edges_only = true gives plain Dijkstra on the edge graph (kept for comparison and tests).
// The march also stops once max_vertices vertices are final (a vertex budget: order() then holds
// the max_vertices nearest ones, and the last of them tells the radius reached).
void geodesic_distance(const SurfaceMesh& mesh, const std::vector<std::pair<Vertex, double>>& seeds,
                       double max_distance, GeodesicWorkspace& ws, bool edges_only = false,
                       size_t max_vertices = SIZE_MAX);

// Distance at C from the unfolded triangle (A, B, C) with known distances dA, dB; the smaller
// edge update when the straight path from the virtual source misses segment AB.
double triangle_update(const Point& a, const Point& b, const Point& c, double da, double db);

}  // namespace adasculpt::deform
