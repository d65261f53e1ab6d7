#include "sculpt/grab.h"
#include "mesh/clock.h"

#include <algorithm>
#include <chrono>
#include <limits>

namespace adasculpt::sculpt {

namespace {
}  // namespace

FramePlan plan_frame(size_t region_vertices, bool sizing_due, const deform::DeformOptions& options) {
  FramePlan plan;
  const double n = double(region_vertices);
  plan.region_work = n * (FramePlan::kRegionWorkPerVertex + (sizing_due ? FramePlan::kSizingWorkPerVertex : 0.0));
  plan.field.work = std::max(options.frame_work - plan.region_work, FramePlan::kMinFieldFraction * options.frame_work);
  // A frame whose region work leaves the field only its minimum share (a grab's first frames
  // remesh the whole region) defers too: the ordering of the field's system, run in one piece,
  // added 20M instructions to the held-out pull's first two frames.
  plan.field.defer_large_steps = sizing_due || plan.region_work + plan.field.work > options.frame_work;
  return plan;
}

void Grab::begin(const mesh::SurfaceMesh& mesh, const Point& picked, mesh::Face picked_face, double handle_radius,
                 double roi_radius) {
  deformer_.begin(mesh, picked, picked_face, handle_radius, roi_radius);
  strain_.reset();
  scope_.clear();
  footprint_.clear();
  if (++grab_ == 0) {  // (stamps of 2^32 grabs ago could match)
    std::fill(footprint_stamp_.begin(), footprint_stamp_.end(), 0u);
    grab_ = 1;
  }
  dragged_ = false;
  deferred_in_a_row_ = 0;
}

// One remeshing iteration on scope_ (RegionStrain::select's), then the region follows its edits.
remesh::IterationStats Grab::remesh_scope(mesh::SurfaceMesh& mesh, remesh::Remesher& remesher,
                                          std::vector<mesh::Vertex>& region) {
  const remesh::IterationStats st = remesher.iterate_region(scope_);
  strain_.update_region(mesh, region, scope_);
  return st;
}

void Grab::drag(mesh::SurfaceMesh& mesh, remesh::Remesher& remesher, const deform::HandleTransform& total,
                double epsilon, FrameTimings& f, ChangeSet& changes) {
  const auto t0 = Clock::now();
  const size_t faces_before = mesh.faces_size();
  // The field's solve fills what the region's work leaves of the frame (FramePlan): with a fixed
  // share, a frame whose region iteration measured the whole sizing again (every 4th; 20M
  // instructions on a 10k-vertex ROI, now spread over the frames for such a region) had 1.5x the
  // instructions of the others, and the first frames of a grab (largest region) 2x the last.
  // The region work is planned from the recent frames' remeshing scopes (the first frame remeshes
  // the whole region, sculpt/region_strain.h): the larger of the last one and their running mean,
  // since the strained vertices come due in waves (the held-out pull's scope went from 2k to 7k
  // vertices between two frames, and that frame's field had been given the 2k frame's share).
  const size_t planned = dragged_ ? std::max(scope_.size(), size_t(scope_mean_)) : deformer_.last().region.size();
  plan_ = plan_frame(planned, remesher.sizing_due(), deformer_.options());
  // Never defer for long: the field's solve must go on even when every frame is heavy.
  if (plan_.field.defer_large_steps && ++deferred_in_a_row_ > kMaxDeferredFrames) plan_.field.defer_large_steps = false;
  if (!plan_.field.defer_large_steps) deferred_in_a_row_ = 0;
  deform::StepResult& r = deformer_.step(mesh, total, epsilon, plan_.field);
  const auto t1 = Clock::now();
  strain_.select(mesh, r.region, deformer_.options().remesh_strain, scope_);
  const remesh::IterationStats st = remesh_scope(mesh, remesher, r.region);
  if (footprint_stamp_.size() < mesh.vertices_size()) footprint_stamp_.resize(mesh.vertices_size(), 0u);
  for (mesh::Vertex v : r.region)
    if (footprint_stamp_[v.idx] != grab_) {
      footprint_stamp_[v.idx] = grab_;
      footprint_.push_back(v);
    }
  scope_mean_ = dragged_ ? 0.75 * scope_mean_ + 0.25 * double(scope_.size()) : double(scope_.size());
  dragged_ = true;
  f = FrameTimings{};
  f.roi_ms = r.roi_ms;
  f.field_ms = r.field_ms;
  f.refine_ms = r.refine_ms;
  f.deform_ms = r.deform_ms;
  f.remesh_ms = ms_since(t1);
  f.total_ms = ms_since(t0);
  f.roi_capped = r.roi_capped;
  f.roi_vertices = int(r.n_handle + r.n_free);
  f.field_refreshed = r.field_refreshed;
  f.remeshed_vertices = int(scope_.size());
  f.refine_splits = int(r.splits);
  f.splits = int(st.splits);
  f.collapses = int(st.collapses);
  f.flips = int(st.flips);
  if (st.splits + st.collapses + st.flips > 0 || mesh.faces_size() != faces_before) changes.topology_changed = true;
  changes.touched_vertices.insert(changes.touched_vertices.end(), r.region.begin(), r.region.end());
}

void Grab::end(mesh::SurfaceMesh& mesh, remesh::Remesher& remesher, ChangeSet& changes) {
  if (dragged_) {
    footprint_.erase(std::remove_if(footprint_.begin(), footprint_.end(), [&](mesh::Vertex v) { return mesh.is_deleted(v); }),
                     footprint_.end());
    for (int pass = 0; pass < kSettlePasses; ++pass) {
      strain_.select_release(mesh, footprint_, kMendAngleDeg, scope_);
      if (scope_.empty()) break;
      const size_t faces_before = mesh.faces_size();
      const remesh::IterationStats st = remesh_scope(mesh, remesher, footprint_);
      if (st.splits + st.collapses + st.flips > 0 || mesh.faces_size() != faces_before) changes.topology_changed = true;
      changes.touched_vertices.insert(changes.touched_vertices.end(), scope_.begin(), scope_.end());
    }
  }
  dragged_ = false;
  deformer_.end();
}

}  // namespace adasculpt::sculpt
