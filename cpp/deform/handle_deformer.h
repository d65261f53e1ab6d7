#pragma once
// One handle-based deformation step per frame (PAPER.md section 4), to be interleaved with one
// remeshing iteration on the returned region.
//
// begin() fixes the handle centre (a surface point) and the two geodesic radii. Each step():
//  1. ROI: geodesic distance (geodesic.h) from the centre on the current mesh, cut at the ROI
//     radius and at a vertex budget (max_roi_vertices: a larger ROI is shrunk to the budget's
//     radius, the handle with it, and the step reports roi_capped): handle = within
//     handle_radius, free = the rest of the ROI, fixed = two rings of vertices outside the ROI
//     (two, because the bi-Laplacian stencil reaches two rings).
//  2. Field: the biharmonic blending field w (1 on the handle, 0 on the fixed rings) on the
//     current surface (biharmonic_solver.h). Two ways (DeformOptions::field_solve):
//     - EveryFrame, as in the paper: ROI and field recomputed from scratch every frame (a sparse
//       factorisation, 50-100 ms on a 10k-vertex ROI: the frame-time tail of issue 18).
//     - Carried (default): ROI and field are carried through the edits between refreshes
//       (below; the ROI is measured again on the current surface at each): vertices the remesher
//       removes leave, vertices it adds take the mean of their known neighbours (a split's new
//       vertex sits between its edge's ends), a collapse's survivor keeps its value, the
//       refinement's midpoints keep the refinement's estimate. The field starts from the
//       rotationally symmetric biharmonic profile of the geodesic distance (the exact solution
//       on a flat disc) and is replaced, again and again, by exact solves of the current region
//       on the current surface, each spread over several frames (BiharmonicSolver's amortised
//       solve, each frame its FieldShare: field_work_per_frame, or in a grab what the frame's
//       other work leaves, sculpt/grab.h): no frame pays for a whole factorisation, and the
//       field is at most one solve's duration behind the surface (about 7 frames for a
//       10k-vertex ROI in a grab's plan). Warm-started CG on the
//       bi-Laplacian was tried first and dropped: with a Jacobi preconditioner 30 steps a frame
//       left a field error of 0.08 after 60 frames (it only removes local error; the
//       bi-Laplacian's condition number grows as h^-4).
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

enum class FieldSolve {
  Carried,     // carried through the edits, corrected by a few CG steps per frame (default)
  EveryFrame,  // ROI and field from scratch every frame (the paper; for comparison)
};

struct DeformOptions {
  FieldSolve field_solve = FieldSolve::Carried;
  // Carried: the work each frame gives the amortised exact solve, in multiply-adds (counted, not
  // timed, so that a grab is reproducible; 3e6 is about 2-3 ms natively). At least one step of
  // it runs per frame, the longest being the ordering of a 10k-vertex ROI (~3 ms).
  double field_work_per_frame = 3e6;
  // Carried, in a grab (sculpt/grab.h): the work of a whole frame in the same unit. The field's
  // share is what the frame's refinement and region iteration (estimated from the size of the
  // recent frames' remeshing scopes) leave of it, so that heavy and light frames cost alike: 3.3e6
  // is about 35-40M instructions, the frames of a 10k-vertex ROI's pull 6-10 ms natively on this
  // project's 2-core machine. (It was 5e6 while every frame remeshed the whole region; at 3e6 the
  // held-out pull's field was not solved once in 60 frames.)
  double frame_work = 3.3e6;
  // Vertex budget of the ROI (handle + free vertices) at its computation; 0 = no budget.
  size_t max_roi_vertices = 20000;
  // In a grab (sculpt/grab.h, sculpt/region_strain.h): a vertex of the region is remeshed again
  // once the strain of the edges around it, accumulated since it last was, reaches this (0.1: an
  // edge stretched by 10 % or turned by 6 degrees); 0 = the whole region every frame (the paper).
  double remesh_strain = 0.1;
  // EveryFrame: the factorisation reuse of the exact solve (biharmonic_solver.h).
  FieldReuse reuse = FieldReuse::Exact;
  int max_refinement_steps = 20;       // CarryFactorization only: PCG steps before refactorising
  double refinement_tolerance = 1e-4;  // relative residual of the carried factorisation
  bool refine = true;                  // the midpoint test of step 3
  bool edges_only_distance = false;    // plain Dijkstra instead of the triangle update (comparison)
};

// A frame's share of the carried field's amortised solve (FieldSolve::Carried only).
struct FieldShare {
  double work = -1;  // multiply-adds; < 0: DeformOptions::field_work_per_frame
  // The frame's other work is heavier than usual: the restart of a finished refresh (a new ROI
  // and system) and a one-piece solver step larger than `work` wait for the next frame.
  bool defer_large_steps = false;
};

struct StepResult {
  double roi_ms = 0, field_ms = 0, refine_ms = 0, deform_ms = 0;
  size_t n_handle = 0, n_free = 0, n_fixed = 0, splits = 0;
  BiharmonicStats field_stats;
  // The ROI was cut to max_roi_vertices: roi_radius is the radius it reached (else the radius
  // asked for), handle_radius shrunk in proportion.
  bool roi_capped = false;
  double roi_radius = 0, handle_radius = 0;
  // Carried: this frame applied a finished exact solve; how many so far in this grab.
  bool field_refreshed = false;
  int field_refreshes = 0;
  // Carried: the multiply-adds this frame's share of the solve did (the steps that run in one
  // piece by their estimate; the numeric rows may pass the share by one row).
  double field_work = 0;
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
  // The ROI's seed is the vertex nearest to picked: a corner of picked_face (a face the point
  // lies on, e.g. from the session's AABB tree), or without one, a scan of every vertex.
  void begin(const SurfaceMesh& mesh, const Point& picked, mesh::Face picked_face, double handle_radius,
             double roi_radius);
  void begin(const SurfaceMesh& mesh, const Point& picked, double handle_radius, double roi_radius) {
    begin(mesh, picked, mesh::Face(), handle_radius, roi_radius);
  }
  // One frame; `total` is the transform since begin(). Edits the mesh (splits, positions).
  // share: this frame's part of the carried field's solve (by default field_work_per_frame;
  // a grab gives it what the frame's other work leaves, sculpt/grab.h).
  StepResult& step(SurfaceMesh& mesh, const HandleTransform& total, double epsilon, FieldShare share = {});
  // Steps 1-2 only (no refinement, no deformation): for tests and for measuring the field.
  void compute_region_and_field(const SurfaceMesh& mesh);
  // Step 2 only, on the region of the last call (same vertices; geometry may have changed):
  // a full solve.
  void recompute_field(const SurfaceMesh& mesh);
  void end();
  bool active() const { return active_; }
  // The largest |w - w_full| over the free vertices of the last field computation, where w_full
  // solves that same system exactly (a factorisation: for measurements and tests only). May be
  // called between steps, after the remesher's edits of the region.
  double field_error_vs_full_solve(const SurfaceMesh& mesh);

  const Point& center() const { return center_; }
  const HandleTransform& total() const { return previous_total_; }
  // Field of the last step (1 handle, 0 fixed and outside).
  double field(Vertex v) const;
  const std::vector<Vertex>& handle_vertices() const { return handle_; }
  const std::vector<Vertex>& free_vertices() const { return free_; }
  const std::vector<Vertex>& fixed_vertices() const { return fixed_; }  // ring 1 then ring 2
  const GeodesicWorkspace& distances() const { return geodesic_; }
  const StepResult& last() const { return result_; }
  // The region of the last step (last().region), for the caller to edit in place between steps
  // (see StepResult::region).
  std::vector<mesh::Vertex>& region() { return result_.region; }
  DeformOptions& options() { return options_; }
  BiharmonicSolver& solver() { return solver_; }

 private:
  enum Category : std::uint8_t { kOutside = 0, kHandle, kFree, kRing1, kRing2 };
  Vertex find_seed(const SurfaceMesh& mesh) const;
  void compute_region(const SurfaceMesh& mesh);
  void assemble_system(const SurfaceMesh& mesh);
  void compute_field(const SurfaceMesh& mesh);
  void start_refresh(const SurfaceMesh& mesh);
  void refresh_region(const SurfaceMesh& mesh);
  void apply_refresh(const SurfaceMesh& mesh);
  void store_field();
  void start_from_radial_profile();
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
  bool restart_pending_ = false;  // a refresh finished last frame: the next one starts this frame
  double handle_radius_used_ = 0, roi_radius_used_ = 0;  // after the vertex budget

  GeodesicWorkspace geodesic_;
  BiharmonicSolver solver_;
  BiharmonicSystem system_;
  std::vector<double> solution_;
  std::vector<Vertex> handle_, free_, fixed_;
  std::vector<Vertex> row_vertices_;
  // The amortised solve in progress: its free vertices and rows, stamped refresh_id_.
  std::vector<Vertex> refresh_free_, refresh_rows_;
  std::vector<std::uint32_t> refresh_stamp_;
  std::uint32_t refresh_id_ = 0;
  std::vector<double> carried_;  // refresh_region's scratch  // the system's rows of the last assembly (their row_index_ is set)
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
