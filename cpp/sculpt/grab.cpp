#include "sculpt/grab.h"

#include <chrono>

namespace adasculpt::sculpt {

namespace {
using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }
}  // namespace

void Grab::begin(const mesh::SurfaceMesh& mesh, const Point& picked, mesh::Face picked_face, double handle_radius,
                 double roi_radius) {
  deformer_.begin(mesh, picked, picked_face, handle_radius, roi_radius);
}

void Grab::drag(mesh::SurfaceMesh& mesh, remesh::Remesher& remesher, const deform::HandleTransform& total,
                double epsilon, FrameTimings& f, ChangeSet& changes) {
  const auto t0 = Clock::now();
  const size_t faces_before = mesh.faces_size();
  // A frame whose region iteration measures the sizing again (every 4th; 20M instructions on a
  // 10k-vertex ROI) gives the field's solve half its share: those frames were the p95.
  deform::StepResult& r = deformer_.step(mesh, total, epsilon, remesher.sizing_due() ? 0.5 : 1.0);
  const auto t1 = Clock::now();
  const remesh::IterationStats st = remesher.iterate_region(r.region);
  f = FrameTimings{};
  f.roi_ms = r.roi_ms;
  f.field_ms = r.field_ms;
  f.refine_ms = r.refine_ms;
  f.deform_ms = r.deform_ms;
  f.remesh_ms = ms_since(t1);
  f.total_ms = ms_since(t0);
  f.roi_capped = r.roi_capped;
  f.roi_vertices = int(r.n_handle + r.n_free);
  if (st.splits + st.collapses + st.flips > 0 || mesh.faces_size() != faces_before) changes.topology_changed = true;
  changes.touched_vertices.insert(changes.touched_vertices.end(), r.region.begin(), r.region.end());
}

void Grab::end() { deformer_.end(); }

}  // namespace adasculpt::sculpt
