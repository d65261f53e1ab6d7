#include "sculpt/grab.h"

#include <algorithm>
#include <chrono>

namespace adasculpt::sculpt {

namespace {
using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }
}  // namespace

FramePlan plan_frame(size_t region_vertices, bool sizing_due, const deform::DeformOptions& options) {
  FramePlan plan;
  const double n = double(region_vertices);
  plan.region_work = n * (FramePlan::kRegionWorkPerVertex + (sizing_due ? FramePlan::kSizingWorkPerVertex : 0.0));
  plan.field.work = std::max(options.frame_work - plan.region_work, FramePlan::kMinFieldFraction * options.frame_work);
  plan.field.defer_large_steps = sizing_due;
  return plan;
}

void Grab::begin(const mesh::SurfaceMesh& mesh, const Point& picked, mesh::Face picked_face, double handle_radius,
                 double roi_radius) {
  deformer_.begin(mesh, picked, picked_face, handle_radius, roi_radius);
}

void Grab::drag(mesh::SurfaceMesh& mesh, remesh::Remesher& remesher, const deform::HandleTransform& total,
                double epsilon, FrameTimings& f, ChangeSet& changes) {
  const auto t0 = Clock::now();
  const size_t faces_before = mesh.faces_size();
  // The field's solve fills what the region's work leaves of the frame (FramePlan): with a fixed
  // share, a frame whose region iteration measured the whole sizing again (every 4th; 20M
  // instructions on a 10k-vertex ROI, now spread over the frames for such a region) had 1.5x the
  // instructions of the others, and the first frames of a grab (largest region) 2x the last.
  plan_ = plan_frame(deformer_.last().region.size(), remesher.sizing_due(), deformer_.options());
  deform::StepResult& r = deformer_.step(mesh, total, epsilon, plan_.field);
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
  f.refine_splits = int(r.splits);
  f.splits = int(st.splits);
  f.collapses = int(st.collapses);
  f.flips = int(st.flips);
  if (st.splits + st.collapses + st.flips > 0 || mesh.faces_size() != faces_before) changes.topology_changed = true;
  changes.touched_vertices.insert(changes.touched_vertices.end(), r.region.begin(), r.region.end());
}

void Grab::end() { deformer_.end(); }

}  // namespace adasculpt::sculpt
