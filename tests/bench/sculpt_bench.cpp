// Sculpting frame on a 100k-triangle mesh: a pull with an ROI of about 10k vertices, each frame
// = ROI + field + refinement + deformation + one local remeshing iteration (Session::grab_drag).
// Prints the median frame and the phase split. Mesh: the shared dragon, or an icosphere(6)
// (82k triangles) when ../shared/meshes is absent.
//   build/native/adasculpt_bench --benchmark_filter=Sculpt
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "deform/geodesic.h"
#include "deform/handle_deformer.h"
#include "io/load_mesh.h"
#include "remesh/remesher.h"
#include "mesh/primitives.h"
#include "sculpt/session.h"

namespace {

using namespace adasculpt;
using mesh::Vertex;

struct Setup {
  mesh::SurfaceMesh mesh;
  std::string name;
  Point center{0.0};
  Vec3 normal{0.0};
  double roi_radius = 0, handle_radius = 0;
};

// The geodesic radius around the picked vertex that holds `target` vertices.
const Setup& setup() {
  static const Setup s = [] {
    Setup r;
    const std::string path = std::string(ADASCULPT_SHARED_MESHES_DIR) + "/dragon.off";
    if (std::filesystem::exists(path)) {
      r.mesh = io::load_mesh(path);
      r.name = "dragon";
    } else {
      r.mesh = mesh::make_icosphere(6);
      r.name = "icosphere(6)";
    }
    // A sculpting session works on a mesh the remesher has already adapted (the app remeshes
    // on demand, and every frame keeps the touched region adapted); the raw scan would make
    // the first frames of every grab re-triangulate the whole ROI.
    remesh::remesh(r.mesh, remesh::default_options_for(r.mesh));
    // Pick the vertex with the largest y (the dragon's back), a convex spot to pull from.
    Vertex pick(0);
    for (Vertex v : r.mesh.vertices())
      if (r.mesh.position(v).y > r.mesh.position(pick).y) pick = v;
    r.center = r.mesh.position(pick);
    deform::GeodesicWorkspace ws;
    deform::geodesic_distance(r.mesh, {{pick, 0.0}}, 1e300, ws);
    const size_t target = std::min<size_t>(10000, ws.order().size() - 1);
    r.roi_radius = ws.distance(ws.order()[target]);
    r.handle_radius = 0.15 * r.roi_radius;
    r.normal = Vec3(0, 1, 0);
    return r;
  }();
  return s;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

void BM_SculptPullFrame(benchmark::State& state) {
  const Setup& s = setup();
  sculpt::Session session;
  session.load(s.mesh);
  const int frames_per_grab = 20;
  const double pull = 0.5 * s.roi_radius;  // in total, over a grab
  std::vector<double> total, roi, field, refine, deform, remesh;
  int frame = 0;
  size_t roi_vertices = 0;
  for (auto _ : state) {
    if (frame % frames_per_grab == 0) {
      state.PauseTiming();
      if (session.grabbing()) {
        session.grab_end();
        session.undo();  // every grab starts from the input mesh
      }
      session.grab_begin(s.center, s.handle_radius, s.roi_radius);
      state.ResumeTiming();
    }
    ++frame;
    deform::HandleTransform t;
    t.translation = pull * double((frame - 1) % frames_per_grab + 1) / frames_per_grab * s.normal;
    session.grab_drag(t);
    const sculpt::FrameTimings& f = session.last_frame();
    total.push_back(f.total_ms);
    roi.push_back(f.roi_ms);
    field.push_back(f.field_ms);
    refine.push_back(f.refine_ms);
    deform.push_back(f.deform_ms);
    remesh.push_back(f.remesh_ms);
    roi_vertices = session.changes().touched_vertices.size();
    session.clear_changes();
  }
  state.counters["frame_ms_median"] = median(total);
  state.counters["roi_ms"] = median(roi);
  state.counters["field_ms"] = median(field);
  state.counters["refine_ms"] = median(refine);
  state.counters["deform_ms"] = median(deform);
  state.counters["remesh_ms"] = median(remesh);
  state.counters["region_vertices"] = double(roi_vertices);
  std::printf("%s (%zu faces), ROI radius %.4g: median frame %.2f ms = roi %.2f + field %.2f + refine %.2f + deform %.2f "
              "+ remesh %.2f (region %zu vertices, %zu frames)\n",
              s.name.c_str(), s.mesh.n_faces(), s.roi_radius, median(total), median(roi), median(field),
              median(refine), median(deform), median(remesh), roi_vertices, total.size());
}
BENCHMARK(BM_SculptPullFrame)->Unit(benchmark::kMillisecond)->Iterations(60);

// The field alone on the 10k-vertex ROI: analysis + factorisation (first frame), factorisation
// with the analysis reused (same pattern), and the carried factorisation (old factors +
// iterative refinement) after a small deformation, with its error against a full solve.
void BM_SculptFieldReuse(benchmark::State& state) {
  const Setup& s = setup();
  mesh::SurfaceMesh m = s.mesh;
  deform::DeformOptions exact_opt, carry_opt;
  carry_opt.reuse = deform::FieldReuse::CarryFactorization;
  deform::HandleDeformer exact(exact_opt), carry(carry_opt);
  std::vector<double> first, refactor, carried, err;
  int steps = 0;
  for (auto _ : state) {
    exact.begin(m, s.center, s.handle_radius, s.roi_radius);
    carry.begin(m, s.center, s.handle_radius, s.roi_radius);
    exact.compute_region_and_field(m);
    first.push_back(exact.last().field_stats.analyze_ms + exact.last().field_stats.factorize_ms);
    carry.compute_region_and_field(m);
    // A small deformation of the ROI (one frame of a pull): same topology, new cotan weights.
    mesh::SurfaceMesh moved = m;
    for (Vertex v : exact.free_vertices()) moved.position(v) += 0.01 * s.roi_radius * exact.field(v) * s.normal;
    exact.recompute_field(moved);
    refactor.push_back(exact.last().field_stats.factorize_ms + exact.last().field_stats.solve_ms);
    carry.recompute_field(moved);
    carried.push_back(carry.last().field_stats.solve_ms);
    steps = carry.last().field_stats.refinement_steps;
    double e = 0;
    for (Vertex v : exact.free_vertices()) e = std::max(e, std::abs(exact.field(v) - carry.field(v)));
    err.push_back(e);
  }
  state.counters["analyze_factorize_ms"] = median(first);
  state.counters["refactorize_ms"] = median(refactor);
  state.counters["carried_ms"] = median(carried);
  state.counters["carried_max_error"] = median(err);
  std::printf("field on %zu free vertices: analyse+factorise %.2f ms, factorise+solve (pattern reused) %.2f ms, "
              "carried factors + %d refinement steps %.2f ms, max |w_carried - w_full| = %.2e\n",
              exact.free_vertices().size(), median(first), median(refactor), steps, median(carried), median(err));
}
BENCHMARK(BM_SculptFieldReuse)->Unit(benchmark::kMillisecond)->Iterations(5);

}  // namespace
