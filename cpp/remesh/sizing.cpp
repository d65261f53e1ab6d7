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

namespace {
double longest_edge(const Point c[3]) {
  return std::sqrt(std::max({glm::dot(c[1] - c[0], c[1] - c[0]), glm::dot(c[2] - c[1], c[2] - c[1]),
                             glm::dot(c[0] - c[2], c[0] - c[2])}));
}
// How far the triangle is into the coarse regime: 0 up to kFineTriangle x its smallest value, 1
// from kCoarseTriangle x, linear between (neighbouring triangles of different sizes then differ
// less in the rule they follow).
double coarseness(const Point corner[3], const double value[3]) {
  const double ratio = longest_edge(corner) / std::max(std::min({value[0], value[1], value[2]}), 1e-300);
  return std::clamp((ratio - kFineTriangle) / (kCoarseTriangle - kFineTriangle), 0.0, 1.0);
}
// Largest number of parts an edge of a coarse triangle is cut into for the estimate: 32^2 samples.
constexpr int kMaxEstimateDivisions = 32;
}  // namespace

double sizing_inside_triangle(const Point corner[3], const double value[3], const Point& p, const double bary[3],
                              double gradation, double max_length) {
  const double interpolated = bary[0] * value[0] + bary[1] * value[1] + bary[2] * value[2];
  const double weight = coarseness(corner, value);
  if (weight == 0) return interpolated;
  double graded = max_length;
  for (int i = 0; i < 3; ++i) graded = std::min(graded, value[i] + gradation * glm::length(p - corner[i]));
  return interpolated + weight * std::max(0.0, graded - interpolated);
}

double inverse_square_sizing_integral(const Point corner[3], const double value[3], double gradation,
                                      double max_length) {
  const double area = 0.5 * glm::length(glm::cross(corner[1] - corner[0], corner[2] - corner[0]));
  auto inverse_square = [](double l) { return 1.0 / std::max(l * l, 1e-300); };
  if (coarseness(corner, value) == 0)
    return area * (inverse_square(value[0]) + inverse_square(value[1]) + inverse_square(value[2])) / 3.0;
  // The n^2 triangles of the regular subdivision, each sampled at its centroid: n(n+1)/2 upward
  // ones at ((i + 1/3) / n, (j + 1/3) / n), n(n-1)/2 downward at ((i + 2/3) / n, (j + 2/3) / n).
  const double smallest = std::min({value[0], value[1], value[2]});
  const int n = static_cast<int>(
      std::min<double>(kMaxEstimateDivisions, std::ceil(longest_edge(corner) / std::max(smallest, 1e-300))));
  double sum = 0;
  auto sample = [&](double u, double v) {
    const double bary[3] = {1.0 - u - v, u, v};
    const Point p = bary[0] * corner[0] + bary[1] * corner[1] + bary[2] * corner[2];
    sum += inverse_square(sizing_inside_triangle(corner, value, p, bary, gradation, max_length));
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; i + j < n; ++j) {
      sample((i + 1.0 / 3.0) / n, (j + 1.0 / 3.0) / n);
      if (i + j + 1 < n) sample((i + 2.0 / 3.0) / n, (j + 2.0 / 3.0) / n);
    }
  return area * sum / (double(n) * n);
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
