#include "remesh/sizing.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

namespace adasculpt::remesh {

double sizing_from_curvature(double kappa, double epsilon, double min_length, double max_length) {
  if (!(kappa > 0.0)) return max_length;
  // The formula is the chord rule for a sphere of radius r = 1/kappa: its value grows with eps up
  // to eps = r (L = sqrt(3) r, the triangle inscribed in a great circle) and falls after it, to 0
  // at eps = 2r. Past r the whole bump lies within eps of any triangle near it, and the detail is
  // below the tolerance: the field keeps sqrt(3) eps there. Using the falling branch (or
  // min_length where it had no real solution) asked for the SHORTEST edges exactly where a coarse
  // tolerance meets a noisy scan: bunny at eps 2% of the diagonal got 34,956 vertices, 5% 157k.
  // This way L never shrinks as eps grows, nor grows as kappa grows.
  const double squared = kappa * epsilon < 1.0 ? 6.0 * epsilon / kappa - 3.0 * epsilon * epsilon : 3.0 * epsilon * epsilon;
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
  // A min-heap on storage that outlives the call: a grab runs this every frame (remesher.cpp's
  // sizing slices), and a fresh std::priority_queue reallocated its vector a dozen times a call.
  // A large one (a whole-mesh remesh) is released after use.
  static thread_local std::vector<Item> heap;
  heap.clear();
  struct Queue {
    std::vector<Item>& items;
    bool empty() const { return items.empty(); }
    const Item& top() const { return items.front(); }
    void push(const Item& item) {
      items.push_back(item);
      std::push_heap(items.begin(), items.end(), std::greater<Item>());
    }
    void pop() {
      std::pop_heap(items.begin(), items.end(), std::greater<Item>());
      items.pop_back();
    }
  } queue{heap};
  // On the flat arrays: the seeding visits every edge of a sculpting frame's region.
  const auto* hc = mesh.halfedge_connectivity_data();
  const mesh::Halfedge* vh = mesh.vertex_halfedge_data();
  const Point* pos = mesh.positions().data();
  double* size = sizing.vector().data();
  const std::uint8_t* in = inside ? inside->data() : nullptr;
  // The bound at w from v's value; a neighbour w can only be lowered by a smaller value (the bound
  // adds a non-negative length), so the length is measured only then: on a uniform field
  // (min_length == max_length) no square root is taken, and the seeding was a tenth of a brush
  // stamp's instructions.
  auto lowers = [&](double value, mesh::Index v, mesh::Index w, double* bound) {
    if (!(value < size[w]) || (in && !in[w])) return false;
    *bound = value + gradation * glm::length(pos[w] - pos[v]);
    return *bound < size[w];
  };
  auto for_each_neighbour = [&](mesh::Index v, auto&& fn) {  // stops when fn returns true
    const mesh::Halfedge start = vh[v];
    if (!start.is_valid()) return;
    mesh::Halfedge h = start;
    do {
      if (fn(hc[h.idx].to.idx)) return;
      h = hc[h.idx ^ 1u].next;
    } while (h != start);
  };
  for (mesh::Vertex v : vertices) {
    const double value = size[v.idx];
    double bound;
    for_each_neighbour(v.idx, [&](mesh::Index w) {
      if (!lowers(value, v.idx, w, &bound)) return false;
      queue.push({value, v.idx});
      return true;
    });
  }
  while (!queue.empty()) {
    // Plain variables, not a structured binding: C++17 lambdas cannot capture those (clang refuses).
    const double value = queue.top().first;
    const mesh::Index v = queue.top().second;
    queue.pop();
    if (value > size[v]) continue;  // stale entry
    for_each_neighbour(v, [&](mesh::Index w) {
      double bound;
      if (lowers(value, v, w, &bound)) {
        size[w] = bound;
        queue.push({bound, w});
      }
      return false;
    });
  }
  if (heap.capacity() > (size_t(1) << 16)) std::vector<Item>().swap(heap);
}

}  // namespace adasculpt::remesh
