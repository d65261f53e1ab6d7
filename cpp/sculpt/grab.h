#pragma once
// The frames of one grab, as the session runs them: the handle deformation (ROI, field,
// refinement, blended transform; deform/handle_deformer.h) followed by one remeshing iteration on
// the deformed region plus a ring (remesh::Remesher::iterate_region), with the timings and the
// changes the session reports. Every step is proportional to the region: nothing here walks the
// whole mesh, per frame or per grab (the seed of the ROI is a corner of the picked face).
#include <cstdint>

#include "deform/handle_deformer.h"
#include "mesh/surface_mesh.h"
#include "remesh/remesher.h"
#include "sculpt/session.h"

namespace adasculpt::sculpt {

class Grab {
 public:
  // picked: the surface point the grab holds, on face `picked_face` (a live face of mesh).
  void begin(const mesh::SurfaceMesh& mesh, const Point& picked, mesh::Face picked_face, double handle_radius,
             double roi_radius);
  // One frame; fills `timings` (every phase, roi_capped) and appends to `changes`.
  void drag(mesh::SurfaceMesh& mesh, remesh::Remesher& remesher, const deform::HandleTransform& total,
            double epsilon, FrameTimings& timings, ChangeSet& changes);
  void end();
  bool active() const { return deformer_.active(); }
  // The field solve (carried by default, or every frame as in the paper) and the ROI's vertex
  // budget; they apply from the next begin().
  deform::DeformOptions& options() { return deformer_.options(); }
  const deform::HandleDeformer& deformer() const { return deformer_; }

 private:
  deform::HandleDeformer deformer_;
};

}  // namespace adasculpt::sculpt
