// Reader/writer throughput on a 100k-triangle mesh (a perturbed 250 x 200 quad
// grid). The file is generated once per format into a temp file and read
// repeatedly, so the numbers include file I/O from the page cache and parsing.

#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <random>
#include <string>

#include "io/mesh_io.h"

namespace {

using adasculpt::io::Format;
using adasculpt::io::PolygonSoup;

PolygonSoup grid_100k() {
  constexpr uint32_t kW = 250, kH = 200;  // 2 * 250 * 200 = 100000 triangles
  PolygonSoup s;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> jitter(-0.25, 0.25);
  // Full-precision coordinates: the writer's output is the worst case for the parser.
  for (uint32_t y = 0; y <= kH; ++y)
    for (uint32_t x = 0; x <= kW; ++x)
      s.points.push_back({x + jitter(rng), y + jitter(rng), jitter(rng)});
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      const uint32_t a = y * (kW + 1) + x, b = a + 1, c = a + kW + 2, d = a + kW + 1;
      s.triangles.push_back({a, b, c});
      s.triangles.push_back({a, c, d});
    }
  return s;
}

// Writes the test file once per format and removes it at exit.
const std::string& temp_file(Format f) {
  struct Files {
    std::map<Format, std::string> paths;
    ~Files() {
      for (auto& [f, p] : paths) std::remove(p.c_str());
    }
  };
  static Files files;
  auto it = files.paths.find(f);
  if (it != files.paths.end()) return it->second;
  static const char* const kExt[] = {"off", "obj", "stl", "ply"};
  const std::string path = "/tmp/adasculpt_bench_100k." + std::string(kExt[static_cast<int>(f)]);
  adasculpt::io::write_soup(path, grid_100k(), f);
  return files.paths[f] = path;
}

void read_bench(benchmark::State& state, Format f) {
  const std::string& path = temp_file(f);
  size_t triangles = 0;
  for (auto _ : state) {
    PolygonSoup s = adasculpt::io::read_soup(path);
    triangles = s.triangles.size();
    benchmark::DoNotOptimize(s.points.data());
  }
  state.counters["triangles"] = double(triangles);
}

void BM_read_obj_100k(benchmark::State& state) { read_bench(state, Format::OBJ); }
void BM_read_off_100k(benchmark::State& state) { read_bench(state, Format::OFF); }
void BM_read_stl_100k(benchmark::State& state) { read_bench(state, Format::STL); }
void BM_read_ply_100k(benchmark::State& state) { read_bench(state, Format::PLY); }

void BM_write_obj_100k(benchmark::State& state) {
  const PolygonSoup s = grid_100k();
  for (auto _ : state) benchmark::DoNotOptimize(adasculpt::io::write_soup_to_memory(s, Format::OBJ).data());
}

BENCHMARK(BM_read_obj_100k)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_read_off_100k)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_read_stl_100k)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_read_ply_100k)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_write_obj_100k)->Unit(benchmark::kMillisecond);

}  // namespace
