// TriangleTree and quality-report timings on the shared dragon (100k triangles).
// Near-surface queries (a vertex moved by up to 1% of the diagonal) are what projection
// after a remeshing step does; uniform queries in the bounding box are the harder case.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "geometry/aabb_tree.h"
#include "geometry/quality.h"
#include "geometry/topology.h"
#include "io/load_mesh.h"

namespace {

using adasculpt::Point;
using adasculpt::Vec3;
using adasculpt::geometry::TriangleTree;
namespace mesh = adasculpt::mesh;

const mesh::SurfaceMesh* dragon() {
  static const mesh::SurfaceMesh* m = [] {
    const std::string path = std::string(ADASCULPT_SHARED_MESHES_DIR) + "/dragon.off";
    return std::filesystem::exists(path) ? new mesh::SurfaceMesh(adasculpt::io::load_mesh(path)) : nullptr;
  }();
  return m;
}

std::vector<Point> queries(const mesh::SurfaceMesh& m, bool near_surface, size_t n) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Point> out;
  Point lo(1e300), hi(-1e300);
  for (mesh::Vertex v : m.vertices()) lo = glm::min(lo, m.position(v)), hi = glm::max(hi, m.position(v));
  const double diag = glm::length(hi - lo);
  for (size_t i = 0; i < n; ++i) {
    if (near_surface) {
      mesh::Vertex v(static_cast<mesh::Index>(rng() % m.vertices_size()));
      out.push_back(m.position(v) + 0.01 * diag * Vec3(u(rng), u(rng), u(rng)));
    } else {
      out.push_back(lo + 0.5 * (Vec3(u(rng), u(rng), u(rng)) + 1.0) * (hi - lo));
    }
  }
  return out;
}

void BM_TreeBuild(benchmark::State& state) {
  if (!dragon()) return state.SkipWithError("dragon.off not found");
  for (auto _ : state) {
    TriangleTree tree;
    tree.build(*dragon());
    benchmark::DoNotOptimize(tree.triangles().data());
  }
}
BENCHMARK(BM_TreeBuild)->Unit(benchmark::kMillisecond);

void BM_ClosestPoint(benchmark::State& state) {
  if (!dragon()) return state.SkipWithError("dragon.off not found");
  TriangleTree tree;
  tree.build(*dragon());
  const std::vector<Point> q = queries(*dragon(), state.range(0) != 0, 100000);
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(tree.closest_point(q[i]));
    i = (i + 1) % q.size();
  }
  state.SetItemsProcessed(state.iterations());
  state.SetLabel(state.range(0) ? "near surface" : "uniform in bbox");
}
BENCHMARK(BM_ClosestPoint)->Arg(1)->Arg(0);

// Projection of a vertex moved slightly, warm-started from its previous closest point.
void BM_ClosestPointWarm(benchmark::State& state) {
  if (!dragon()) return state.SkipWithError("dragon.off not found");
  TriangleTree tree;
  tree.build(*dragon());
  const mesh::SurfaceMesh& m = *dragon();
  std::vector<Point> q;
  std::vector<TriangleTree::ClosestHit> hints;
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-1, 1);
  const double step = 1e-3 * adasculpt::geometry::bounding_box_diagonal(m);
  for (mesh::Vertex v : m.vertices()) {
    hints.push_back(tree.closest_point(m.position(v)));
    q.push_back(m.position(v) + step * Vec3(u(rng), u(rng), u(rng)));
  }
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(tree.closest_point(q[i], hints[i]));
    i = (i + 1) % q.size();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ClosestPointWarm);

void BM_Ray(benchmark::State& state) {
  if (!dragon()) return state.SkipWithError("dragon.off not found");
  TriangleTree tree;
  tree.build(*dragon());
  const std::vector<Point> q = queries(*dragon(), false, 100000);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec3> d(q.size());
  for (Vec3& x : d) x = Vec3(u(rng), u(rng), u(rng));
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(tree.intersect_ray(q[i], d[i]));
    i = (i + 1) % q.size();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Ray);

void BM_QualityReport(benchmark::State& state) {
  if (!dragon()) return state.SkipWithError("dragon.off not found");
  for (auto _ : state) benchmark::DoNotOptimize(adasculpt::geometry::quality_report(*dragon()));
}
BENCHMARK(BM_QualityReport)->Unit(benchmark::kMillisecond);

void BM_DistanceToItself(benchmark::State& state) {
  if (!dragon()) return state.SkipWithError("dragon.off not found");
  for (auto _ : state) benchmark::DoNotOptimize(adasculpt::geometry::distance_between(*dragon(), *dragon()));
}
BENCHMARK(BM_DistanceToItself)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace
