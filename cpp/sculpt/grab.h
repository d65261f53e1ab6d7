#pragma once
// The frames of one grab, as the session runs them: the handle deformation (ROI, field,
// refinement, blended transform; deform/handle_deformer.h) followed by one remeshing iteration on
// the part of the deformed region (ROI plus a ring) that the deformation strained since it was
// last remeshed (sculpt/region_strain.h; Remesher::iterate_region), with the timings and the
// changes the session reports. Every step is proportional to the region: nothing here walks the
// whole mesh, per frame or per grab (the seed of the ROI is a corner of the picked face).
#include <cstdint>

#include "deform/handle_deformer.h"
#include "mesh/surface_mesh.h"
#include "remesh/remesher.h"
#include "sculpt/region_strain.h"
#include "sculpt/session.h"

namespace adasculpt::sculpt {

// The plan of a grab frame, in the field solve's unit (multiply-adds, about 10 instructions each
// natively; counted from sizes, not timed, so that a replay does the same everywhere): the
// refinement and the region iteration cost about kRegionWorkPerVertex per vertex the frame
// remeshes (planned from the recent frames' remeshing scopes, Grab::drag; a large scope measures a
// slice of its sizing in every call, remesher.h), a region iteration
// that measures the sizing of its whole scope again (Remesher::sizing_due: a small region, every
// 4th call) about kSizingWorkPerVertex more; the field's amortised solve gets what is left of
// DeformOptions::frame_work, at least kMinFieldFraction of it. Such a heavier frame also leaves
// the field's restarts and large one-piece steps to the next frame (FieldShare).
struct FramePlan {
  // Calibrated with callgrind (scripts/pull-frames-callgrind.sh -v) on the pulls of the dragon
  // and the held-out armadillo (10-11.5k region vertices): refinement 3-4M instructions, region
  // iteration with its sizing slice and the scope's gradation 32-35M; a whole sizing
  // measurement 18-26M.
  static constexpr double kRegionWorkPerVertex = 330;
  static constexpr double kSizingWorkPerVertex = 190;
  static constexpr double kMinFieldFraction = 0.1;
  double region_work = 0;  // estimated: refinement and region iteration, sizing included
  deform::FieldShare field;
};
FramePlan plan_frame(size_t region_vertices, bool sizing_due, const deform::DeformOptions& options);

class Grab {
 public:
  // picked: the surface point the grab holds, on face `picked_face` (a live face of mesh).
  void begin(const mesh::SurfaceMesh& mesh, const Point& picked, mesh::Face picked_face, double handle_radius,
             double roi_radius);
  // One frame; fills `timings` (every phase, roi_capped) and appends to `changes`.
  void drag(mesh::SurfaceMesh& mesh, remesh::Remesher& remesher, const deform::HandleTransform& total,
            double epsilon, FrameTimings& timings, ChangeSet& changes);
  // The release: settles what the frames' iterations left unfinished, appending to `changes`: at
  // most kSettlePasses region iterations over the vertices whose connectivity the last iteration
  // changed and the corners of the triangles under kMendAngleDeg, with two rings, anywhere in the
  // grab's footprint (every vertex its regions held). The ROI follows the surface as it deforms,
  // and a part that leaves it keeps what the last frame it was in left there: on the pull of
  // cgal/femur.off the worst triangles after the grab (21.8 degrees) lay outside the last ROI.
  void end(mesh::SurfaceMesh& mesh, remesh::Remesher& remesher, ChangeSet& changes);
  // The whole-mesh remesh leaves no triangle under 25 degrees that a vertex move can mend
  // (remesher.cpp's polish); a release gives the grab's footprint the same goal.
  static constexpr double kMendAngleDeg = 25.0;
  bool active() const { return deformer_.active(); }
  // The field solve (carried by default, or every frame as in the paper) and the ROI's vertex
  // budget; they apply from the next begin().
  deform::DeformOptions& options() { return deformer_.options(); }
  const deform::HandleDeformer& deformer() const { return deformer_; }
  deform::HandleDeformer& deformer() { return deformer_; }  // (measurements: field_error_vs_full_solve)
  // The plan of the last frame (its field share and the other work it expected).
  const FramePlan& last_plan() const { return plan_; }

 private:
  remesh::IterationStats remesh_scope(mesh::SurfaceMesh& mesh, remesh::Remesher& remesher,
                                      std::vector<mesh::Vertex>& region);

  deform::HandleDeformer deformer_;
  FramePlan plan_;
  RegionStrain strain_;
  std::vector<mesh::Vertex> scope_;  // the remeshing iteration's part of the region (strain_)
  // Every vertex a frame's region held since begin() (stamped with grab_ per slot; deleted ones
  // are dropped at the release).
  std::vector<mesh::Vertex> footprint_;
  std::vector<std::uint32_t> footprint_stamp_;
  std::uint32_t grab_ = 0;
  bool dragged_ = false;             // a frame ran since begin()
  double scope_mean_ = 0;            // running mean of the scopes' sizes (the frame plan)
  static constexpr int kMaxDeferredFrames = 3;
  // Each pass can leave new vertices of its own splits unrelaxed: with two, a 22.7-degree triangle
  // of the last pass's making stayed on a dragon pull (the same pull on the same mesh with its
  // elements in another order ended at 25.1 degrees); three end at 25.1 both ways.
  static constexpr int kSettlePasses = 3;
  int deferred_in_a_row_ = 0;  // frames in a row whose plan deferred the field's large steps
};

}  // namespace adasculpt::sculpt
