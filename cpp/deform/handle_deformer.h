#pragma once
// One handle-based deformation step per frame (PAPER.md section 4), to be interleaved with one
// remeshing iteration on the returned region.
//
// begin() fixes the handle centre (a surface point) and the two geodesic radii. Each step():
//  1. ROI: geodesic distance (geodesic.h) from the centre on the current mesh, cut at the ROI
//     radius: handle = within handle_radius, free = the rest of the ROI, fixed = two rings of
//     vertices outside the ROI (two, because the bi-Laplacian stencil reaches two rings).
//  2. Field: the biharmonic blending field w (1 on the handle, 0 on the fixed rings), recomputed
//     on the current surface every step so that large edits work (biharmonic_solver.h).
//  3. Refinement: every edge with a free end is tentatively split at its midpoint; the split is
//     kept when the deformed midpoint deviates by more than epsilon from the midpoint of the
//     deformed endpoints. The field at the midpoint is the mean of the endpoints corrected by the
//     field's second derivative along the edge, estimated from its Laplacian at the endpoints
//     (w_mid = (wa + wb)/2 - |e|^2 (Lap wa + Lap wb) / 32 for a locally isotropic quadratic w).
//     With the plain mean, a translation (blended linearly) would move every midpoint exactly
//     onto the deformed chord and a pull would never refine; the correction is what makes the
//     test see the bend. The new vertex keeps that corrected value.
//  4. Deformation by the increment from the previous total transform to this one, blended by w
//     (handle_transform.h: blend). The handle centre moves with the translation.
// Work is proportional to the ROI: nothing global is rebuilt or cleared per step.
#include <cstdint>
#include <vector>

#include "deform/biharmonic_solver.h"
#include "deform/geodesic.h"
#include "deform/handle_transform.h"
#include "mesh/surface_mesh.h"

namespace adasculpt::deform {

struct DeformOptions {
  FieldReuse reuse = FieldReuse::Exact;
  int max_refinement_steps = 20;  // CarryFactorization only: PCG steps before refactorising
  double refinement_tolerance = 1e-4;  // relative residual of the carried solve (field error ~2e-3 on the dragon)
  bool refine = true;            // the midpoint test of step 3
  // ROI and field are recomputed from scratch every this many frames; in the frames between,
  // they are carried on the edited mesh (removed vertices leave, vertices the remesher added take
  // the mean of their neighbours). 1 = every frame, as in the paper. The field changes little
  // from one frame to the next, and its solve is most of a frame's cost (see README figures).
  int field_refresh_frames = 4;
  bool edges_only_distance = false;  // plain Dijkstra instead of the triangle update (comparison)
};

struct StepResult {
  double roi_ms = 0, field_ms = 0, refine_ms = 0, deform_ms = 0;
  size_t n_handle = 0, n_free = 0, n_fixed = 0, splits = 0;
  BiharmonicStats field_stats;
  // The ROI plus one ring (the first fixed ring), for Remesher::iterate_region. The caller may
  // edit it in place (the remesher does); the next step() looks in it for the vertex nearest to
  // the handle centre, so it must only hold vertices of this mesh.
  std::vector<mesh::Vertex> region;
};

class HandleDeformer {
 public:
  explicit HandleDeformer(const DeformOptions& options = {});

  // picked: a point on the surface (e.g. the closest point to a click); radii are geodesic
  // lengths, roi_radius < handle_radius is treated as roi_radius = handle_radius.
  void begin(const SurfaceMesh& mesh, const Point& picked, double handle_radius, double roi_radius);
  // One frame; `total` is the transform since begin(). Edits the mesh (splits, positions).
  StepResult& step(SurfaceMesh& mesh, const HandleTransform& total, double epsilon);
  // Steps 1-2 only (no refinement, no deformation): for tests and for measuring the field.
  void compute_region_and_field(const SurfaceMesh& mesh);
  // Step 2 only, on the region of the last call (same vertices; geometry may have changed).
  void recompute_field(const SurfaceMesh& mesh);
  void end();
  bool active() const { return active_; }

  const Point& center() const { return center_; }
  const HandleTransform& total() const { return previous_total_; }
  // Field of the last step (1 handle, 0 fixed and outside).
  double field(Vertex v) const;
  const std::vector<Vertex>& handle_vertices() const { return handle_; }
  const std::vector<Vertex>& free_vertices() const { return free_; }
  const std::vector<Vertex>& fixed_vertices() const { return fixed_; }  // ring 1 then ring 2
  const GeodesicWorkspace& distances() const { return geodesic_; }
  const StepResult& last() const { return result_; }
  DeformOptions& options() { return options_; }
  BiharmonicSolver& solver() { return solver_; }

 private:
  enum Category : std::uint8_t { kOutside = 0, kHandle, kFree, kRing1, kRing2 };
  Vertex find_seed(const SurfaceMesh& mesh) const;
  void compute_region(const SurfaceMesh& mesh);
  void compute_field(const SurfaceMesh& mesh);
  void carry_region(const SurfaceMesh& mesh);
  double midpoint_field(Vertex a, Vertex b, const Point& pa, const Point& pb) const;
  size_t refine(SurfaceMesh& mesh, const HandleTransform& inc, double epsilon);
  void grow(size_t n);
  Category category(Vertex v) const {
    return v.idx < stamp_.size() && stamp_[v.idx] == frame_ ? Category(category_[v.idx]) : kOutside;
  }
  void set_category(Vertex v, Category c) {
    stamp_[v.idx] = frame_;
    category_[v.idx] = c;
  }

  DeformOptions options_;
  bool active_ = false;
  Point center_{0.0};
  double handle_radius_ = 0, roi_radius_ = 0;
  Vertex begin_seed_;
  HandleTransform previous_total_;
  bool first_frame_ = true;
  int frames_since_solve_ = 0;

  GeodesicWorkspace geodesic_;
  BiharmonicSolver solver_;
  BiharmonicSystem system_;
  std::vector<double> solution_;
  std::vector<Vertex> handle_, free_, fixed_;
  // Per vertex slot, valid when stamp_ == frame_ (never cleared in full).
  std::vector<std::uint32_t> stamp_;
  std::vector<std::uint8_t> category_;
  std::vector<int> index_;  // free: column; row of the bi-Laplacian system in row_index_
  std::vector<int> row_index_;
  std::vector<double> field_;
  std::vector<double> laplacian_;      // Laplacian of the field (rows of the system only)
  std::vector<double> row_laplacian_;  // per system row, from the solver
  std::uint32_t frame_ = 0;
  std::vector<std::pair<Vertex, double>> seeds_;
  std::vector<mesh::Edge> split_edges_;
  StepResult result_;
};

}  // namespace adasculpt::deform
