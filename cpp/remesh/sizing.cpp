#include "remesh/sizing.h"

#include <algorithm>
#include <cmath>
#include <queue>

#include <glm/geometric.hpp>

namespace adasculpt::remesh {

double sizing_from_curvature(double kappa, double epsilon, double min_length, double max_length) {
  if (!(kappa > 0.0)) return max_length;
  double squared = 6.0 * epsilon / kappa - 3.0 * epsilon * epsilon;
  if (squared <= 0.0) return min_length;
  return std::clamp(std::sqrt(squared), min_length, max_length);
}

void limit_sizing_gradation(const mesh::SurfaceMesh& mesh, const std::vector<mesh::Vertex>& vertices,
                            mesh::VertexProperty<double>& sizing, double gradation,
                            const std::vector<std::uint8_t>* inside) {
  // Dijkstra from the smallest values outwards: each vertex is finalised with the smallest
  // bound any neighbour imposes. Only vertices that lower a neighbour start in the queue: one
  // that cannot with its neighbours' first values cannot later either (values only drop), and on
  // a field that is already graded (most of a sculpting frame's region) the queue stays small.
  using Item = std::pair<double, mesh::Index>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  // A neighbour w can only be lowered by a smaller value (the bound adds a non-negative length), so
  // the length is measured only then: on a uniform field (min_length == max_length) no square
  // root is taken, and the seeding was a tenth of a brush stamp's instructions.
  for (mesh::Vertex v : vertices) {
    const double value = sizing[v];
    for (mesh::Vertex w : mesh.vertices(v)) {
      if (!(value < sizing[w]) || (inside && !(*inside)[w.idx])) continue;
      if (value + gradation * glm::length(mesh.position(w) - mesh.position(v)) < sizing[w]) {
        queue.push({value, v.idx});
        break;
      }
    }
  }
  while (!queue.empty()) {
    auto [value, idx] = queue.top();
    queue.pop();
    mesh::Vertex v(idx);
    if (value > sizing[v]) continue;  // stale entry
    for (mesh::Vertex w : mesh.vertices(v)) {
      if (!(value < sizing[w]) || (inside && !(*inside)[w.idx])) continue;
      double bound = value + gradation * glm::length(mesh.position(w) - mesh.position(v));
      if (bound < sizing[w]) {
        sizing[w] = bound;
        queue.push({bound, w.idx});
      }
    }
  }
}

}  // namespace adasculpt::remesh
