// Remeshing timings: the CLI defaults (adaptive, 5 iterations, projection) on the shared
// meshes the targets name, and one iteration without projection on a converged ~100k-vertex
// mesh (the per-frame cost of interactive use). Medians over repetitions; meshes that are not
// present (a clone without ../shared) are skipped with a message.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include "io/load_mesh.h"
#include "mesh/primitives.h"
#include "remesh/remesher.h"

namespace {

namespace mesh = adasculpt::mesh;
namespace remesh = adasculpt::remesh;

const mesh::SurfaceMesh* shared_mesh(const std::string& name) {
  static std::map<std::string, mesh::SurfaceMesh> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return &it->second;
  const std::string path = std::string(ADASCULPT_SHARED_MESHES_DIR) + "/" + name;
  if (!std::filesystem::exists(path)) return nullptr;
  return &cache.emplace(name, adasculpt::io::load_mesh(path)).first->second;
}

void BM_remesh_defaults(benchmark::State& state, const std::string& name) {
  const mesh::SurfaceMesh* input = shared_mesh(name);
  if (!input) {
    state.SkipWithError(("../shared/meshes/" + name + " not found; skipped").c_str());
    return;
  }
  const remesh::RemeshOptions options = remesh::default_options_for(*input);
  size_t faces = 0;
  for (auto _ : state) {
    state.PauseTiming();
    mesh::SurfaceMesh m = *input;
    state.ResumeTiming();
    remesh::remesh(m, options);
    faces = m.n_faces();
  }
  state.counters["faces_out"] = double(faces);
}

// A converged mesh of about 100k vertices: a sphere remeshed uniformly until stable.
void BM_converged_iteration_no_projection(benchmark::State& state) {
  static mesh::SurfaceMesh converged = [] {
    mesh::SurfaceMesh m = mesh::make_icosphere(7, 1.0);  // 163k vertices, coarsened below
    remesh::RemeshOptions o;
    o.adaptive = false;
    o.target_length = 0.0112;  // about 100k vertices on the unit sphere
    o.iterations = 8;
    remesh::remesh(m, o);
    return m;
  }();
  mesh::SurfaceMesh m = converged;
  remesh::RemeshOptions o;
  o.adaptive = false;
  o.target_length = 0.0112;
  o.projection = false;
  remesh::Remesher remesher(m, o);
  remesher.iterate();  // builds the reference once, outside the timed loop
  for (auto _ : state) remesher.iterate();
  state.counters["vertices"] = double(m.n_vertices());
  state.counters["us_per_vertex"] = benchmark::Counter(double(m.n_vertices()), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert) ;
}

}  // namespace

BENCHMARK_CAPTURE(BM_remesh_defaults, fandisk, std::string("fandisk.off"))->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK_CAPTURE(BM_remesh_defaults, bunny, std::string("bunny.off"))->Unit(benchmark::kMillisecond)->Repetitions(3)->ReportAggregatesOnly(true);
BENCHMARK_CAPTURE(BM_remesh_defaults, horse, std::string("horse.off"))->Unit(benchmark::kMillisecond)->Repetitions(3)->ReportAggregatesOnly(true);
BENCHMARK(BM_converged_iteration_no_projection)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
