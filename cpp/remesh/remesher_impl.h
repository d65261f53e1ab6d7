#pragma once
// Internal state of a Remesher, shared by the pass files (split/collapse, flip, relaxation,
// reference). Not part of the public API.
#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <vector>

#include <glm/geometric.hpp>

#include "geometry/aabb_tree.h"
#include "geometry/triangle.h"
#include "mesh/flat_walk.h"
#include "mesh/scratch.h"
#include "mesh/vertex_mask.h"
#include "remesh/crossing_guard.h"
#include "remesh/remesher.h"

namespace adasculpt::remesh {

using mesh::Edge;
using mesh::EdgeProperty;
using mesh::Halfedge;
using mesh::VertexProperty;

// How a vertex may move.
enum VertexClass : std::uint8_t {
  kFree = 0,        // tangential relaxation
  kFeatureLine = 1, // exactly two feature/boundary edges: slides along them
  kCorner = 2,      // any other number of feature edges: never moves, never removed
};
inline VertexClass vertex_class(int feature_edges) {
  return feature_edges == 0 ? kFree : feature_edges == 2 ? kFeatureLine : kCorner;
}

// Turning angle (radians) above which a feature-line vertex counts as a kink of the line, not a
// curve: the sizing does not resolve it as a curve (average_feature_sizing), and it becomes a
// corner that only a collapse keeping the line near the reference may remove (line_guard.cpp).
constexpr double kMaxCurveTurn = M_PI / 6;

// What the current iteration may do to a vertex.
enum Scope : std::uint8_t {
  kOutside = 0,  // untouched
  kActive = 1,   // may move, be removed, get new edges
  kHeld = 2,     // on the border of a region: keeps its position and stays
};

using mesh::for_each_outgoing;  // mesh/flat_walk.h: the passes of a sculpting frame walk every fan of the region this way

// Largest growth of the target edge length per unit distance (see limit_sizing_gradation).
// 0.2 measured best on the shared meshes: 0.4 leaves 22-24 degree minimum angles and 0.25 a mean
// min angle just under 50 on face.off; 0.15 adds triangles for no further gain.
constexpr double kGradation = 0.2;

using geometry::min_angle_sin2;  // geometry/triangle.h: the passes order triangles by it

// One face's terms of the relaxation (equation 6), shared by its three corners.
struct RelaxFace {
  Vec3 normal;            // twice the area, along the normal
  Point weighted_centre;  // weight x barycentre
  double weight;          // area x mean sizing of the corners
  double area2;           // twice the area
};

// The per-frame passes' scratch buffers. They outlive the remesher (reference.cpp: the last
// remesher destroyed on a thread lends them to the next one): a sculpting session makes one
// remesher per stroke, and allocating and zero-filling the per-slot arrays again cost each
// stroke's first stamp about 3 ms of WebAssembly on the 35k-vertex bunny. Between uses face_seen
// holds no value above face_run and kappa_known is all zero, whoever used them last.
struct RemeshScratch {
  std::vector<Vertex> scope_vertices;
  std::vector<Edge> scope_edges;  // every edge of the scope: iterate_region or gather_all_edges, kept by the split pass
  std::vector<Edge> split_recheck;  // split_long_edges: the edges at the vertices its last pass added
  std::vector<mesh::Face> faces_scratch;
  std::vector<double> face_quality;  // per face slot: min_angle_sin2, during flip_for_angles
  std::vector<std::uint32_t> face_seen;  // per face slot: == face_run when face_quality is current
  std::uint32_t face_run = 0;
  std::vector<std::uint64_t> candidates;  // split/collapse passes: sort keys (split_collapse.cpp)
  std::vector<int> valence;
  std::vector<int> valence_excess;  // valence minus its target (4 on the boundary, 6 inside): flip_edges
  std::vector<Point> new_positions;
  std::vector<RelaxFace> relax_faces;  // per face slot, during relax_vertices (where face_seen == face_run)
  std::vector<double> kappa;
  std::vector<std::uint8_t> kappa_known;  // region mode: vertices whose kappa was computed
};

struct Remesher::Impl : RemeshScratch {
  Impl(SurfaceMesh& m, const RemeshOptions& o);
  ~Impl();
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  void swap_scratch_with_pool();  // see RemeshScratch
  // Whole-mesh passes: every live vertex active and in scope_vertices; and back to none.
  void enter_whole_mesh();
  void leave_whole_mesh();

  SurfaceMesh& mesh;
  RemeshOptions opt;
  std::vector<Face>* deleted_faces_log = nullptr;  // Remesher::log_deleted_faces

  // Reference surface: a copy of the mesh when the remesher was made (or last reset), with
  // its sizing per reference point, for projection and for the sizing of new vertices.
  geometry::TriangleTree tree;
  std::vector<double> ref_sizing;  // per tree point
  // Necks narrower than the sizing field (neck.cpp), found since the reference was built: the
  // sizing grows from `size` at `centre` by the gradation limit. ref_near_neck marks the
  // reference points whose sizing a neck lowered.
  struct Neck {
    Point centre;
    double size;
  };
  std::vector<Neck> necks;
  std::vector<std::uint8_t> ref_near_neck;
  // Triangles around each reference point (CSR), for the local projection walk.
  std::vector<std::uint32_t> ref_fan_offset, ref_fan;
  std::vector<std::array<std::uint32_t, 3>> ref_adjacent;  // across each edge of a tree triangle
  // Feature and boundary edges of the reference (pairs of tree points) and, per point, the
  // segments that meet there (CSR): feature vertices are projected onto these lines.
  std::vector<std::array<std::uint32_t, 2>> ref_segments;
  std::vector<std::uint32_t> ref_segment_offset, ref_segment_of_point;
  bool has_reference = false;
  // How far from the reference, in fidelity tolerances, the sliver repair's collapses and flips may
  // take the surface (fix_bad_faces): the Hausdorff target (kFidelityOtherSide). At 4, a run of
  // repairs along a ring of gen/sliver_cylinder each cut the ring a little deeper, 5 tolerances in
  // all, and no later iteration could project it back (Hausdorff 0.51 % of the diagonal at epsilon
  // 0.05 %, min length 0.2 %, target 0.2 %; 0.14 % now). Of 459 sweep runs at 2 against 4 in the
  // last two iterations only: Hausdorff misses 60 -> 50, min angle misses 172 -> 171, the min
  // angle higher in 27 runs, lower in 11.
  static constexpr double kSliverRepairToleranceTimes = 2.0;
  // ---- the vertex budget (budget.cpp)
  RemeshReport report;
  // The budget is kBudgetPerEstimate x the estimate, but at most kLargeBudgetPerEstimate x the
  // estimate + kLargeBudgetSlack (budget.cpp: the memory a large output's overshoot costs), plus
  // kBudgetPerInputVertex x the input and kBudgetConstant.
  static constexpr double kBudgetPerEstimate = 4.0;
  static constexpr double kLargeBudgetPerEstimate = 2.0;
  static constexpr double kLargeBudgetSlack = 20000;
  static constexpr double kBudgetPerInputVertex = 1.0;  // input vertices no collapse can remove
  static constexpr size_t kBudgetConstant = 1000;
  void estimate_vertex_budget();  // from the reference's sizing; build_reference calls it
  size_t splits_allowed() const;  // before the budget is reached (no limit in region calls)
  void note_budget_reached();     // sets the report's warning
  void reserve_for_splits();      // whole-mesh iterations: room in the mesh for splits_allowed()
  bool whole_mesh = false;
  int region_calls_since_sizing = 0;  // the scope is every vertex: iterate edges directly
  bool sizing_spread = false;  // the last region call measured a slice of its scope (iterate_region)
  std::vector<Vertex> sizing_slice;
  bool reference_stale = false;

  // Per-element state kept on the mesh so it follows splits, collapses and compaction.
  VertexProperty<double> sizing;
  VertexProperty<std::uint8_t> vclass;
  VertexProperty<std::uint8_t> scope;
  VertexProperty<std::uint32_t> ref_hint;  // last reference triangle a vertex projected to
  VertexProperty<std::uint32_t> segment_hint;  // last reference feature segment (feature vertices)
  // A vertex the coverage check put on a reference point the surface had left (coverage.cpp):
  // that point's index, else UINT32_MAX. Honoured while the fidelity check is on (whole-mesh
  // adaptive iterations against a current reference; build_reference clears them).
  VertexProperty<std::uint32_t> anchor;
  EdgeProperty<std::uint8_t> feature;      // feature or boundary edge
  // The sculpting mask (mesh/vertex_mask.h), looked up again by every call (a mask operation may
  // add it between calls): fully masked vertices stay outside every scope, so no pass moves them
  // or changes their triangles, and their neighbours hold the border as a region's border does.
  VertexProperty<float> mask;
  bool masked(Vertex v) const { return mesh::fully_masked(mask, v); }
  // Whole-mesh passes: the unmasked neighbours of masked vertices become held (the region border).
  void hold_around_masked();

  // Scratch buffers, reused so iterations do not allocate once warmed up (and those of
  // RemeshScratch outlive the remesher).
  bool active_faces_listed = false;   // faces_scratch is every face with an active corner (relax_vertices)
  std::vector<std::uint32_t> neck_triangles;  // reference_cross_section: the triangles gathered
  std::vector<std::uint32_t> neck_stamp;      // per reference triangle: == neck_run when gathered
  std::uint32_t neck_run = 0;

  // ---- set-up (reference.cpp)
  void build_reference();
  void mark_features();
  void mark_boundary_edges();  // mark_features with features off
  void drop_isolated_features();
  // Before drop_isolated_features: a boundary edge, or (features on) one whose dihedral angle is
  // past the feature angle, given as feature_cos_limit() (above 1 with features off).
  double feature_cos_limit() const;
  bool sharp_or_boundary(Edge e, double cos_limit) const;
  // ---- back to a new remesher's state around changed slots (reset_slots.cpp)
  bool marked_as_new(Edge e, double cos_limit) const;  // the mark mark_features gives e now
  void refresh_marks_around(const std::vector<Vertex>& vertices);
  std::vector<Vertex> reset_ring;  // scratch: the vertices whose class is derived again
  std::vector<Edge> mirror_marked;  // edges enable_mirror marked: disable_mirror unmarks them
  std::vector<std::uint8_t> feature_edges_per_vertex() const;  // per vertex slot, saturating at 255
  void compute_sizing_from_current_surface(const std::vector<Vertex>& vertices);
  // Lowers the sizing of free vertices where the part is thinner than it (thickness.cpp); needs
  // the reference tree (build_reference).
  void clamp_sizing_to_thickness(const std::vector<Vertex>& vertices);
  void clamp_sizing_to_short_lines();  // short border edges between corners (strips.cpp)
  void clamp_sizing_to_strips();  // creases side by side, narrower than the sizing (strips.cpp)
  // min_length == max_length (a constant detail, as the brush comparison and some sculptors use):
  // the clamp gives every free vertex that length whatever its curvature, so none is measured.
  bool clamp_decides_sizing() const { return !(opt.min_length < opt.max_length); }
  void average_feature_sizing(const std::vector<Vertex>& vertices);
  bool hole_smaller_than(Vertex v, double limit) const;  // (reference.cpp)
  double reference_sizing_at(const Point& p, std::uint32_t* hint_triangle) const;
  geometry::TriangleTree::ClosestHit closest_on_reference(const Point& p, std::uint32_t hint,
                                                          const Vec3* facing = nullptr, double far = 0) const;
  geometry::TriangleTree::ClosestHit walk_reference(const Point& p, std::uint32_t hint) const;
  void project(Vertex v);
  void project(Vertex v, const Vec3& fan_normal);  // free vertices: fan_shape(v).normal
  void project_onto_feature_line(Vertex v);
  // ---- feature lines and the boundary kept within the tolerance (line_guard.cpp)
  // The reference feature segment nearest to p, walking from `hint` (every segment without one).
  std::uint32_t nearest_line_segment(const Point& p, std::uint32_t hint) const;
  // Line vertices whose line turns sharper than a curve (the kinks of a border or feature line)
  // become corners that collapses along the line may still remove (collapse_topology_ok).
  void mark_line_kinks();
  void mark_reference_tips();  // tips sharper than a cube's corner become corners (tips.cpp)
  // A vertex with two feature edges: a line's vertex, or a corner where the line turns by more than
  // kMaxCurveTurn (a kink).
  VertexClass class_of_line_vertex(Vertex v) const;
  // v's class from the feature edges it has now (after an edit that removed one of them).
  VertexClass class_by_lines(Vertex v) const;
  bool is_line_kink(Vertex v) const;  // a corner with exactly two feature edges
  // Whether collapsing h along its feature line keeps the line within surface_tolerance() of the
  // reference line (true without a current reference, or for a free vertex).
  bool line_collapse_stays_near_reference(Halfedge h) const;
  // After the projection: line vertices whose slide took the line farther than the tolerance from
  // the reference line go back to before_slide (per scope vertex). Returns those undone.
  size_t undo_line_slides(const std::vector<Point>& before_slide);
  bool line_guard_active() const;  // whole-mesh iterations with a current reference that has lines
  bool line_neighbours(Vertex v, Vertex ends[2]) const;
  // Whether the reference line points strictly between the segments `from` and `to` all lie
  // within the tolerance of the segment ab (false when the line between is too long to search).
  bool line_points_near_segment(std::uint32_t from, std::uint32_t to, const Point& a, const Point& b) const;

  // ---- necks narrower than the sizing (neck.cpp)
  bool refine_neck_at(Edge e);
  bool loop_separates_large_parts(Vertex a, Vertex b, Vertex w);
  double reference_cross_section(const Point& centre, const Vec3& axis, double radius,
                                 std::initializer_list<std::uint32_t> seeds);
  void lower_reference_sizing(const Point& centre, double size, std::initializer_list<std::uint32_t> triangles);
  double sizing_of_hit(const geometry::TriangleTree::ClosestHit& hit) const;

  // ---- zero-area input triangles (degenerate.cpp): collapses and flips that leave the surface
  // as it is; returns the repairs done. Before the reference is built, without the crossing guard.
  size_t remove_degenerate_faces();
  bool remove_border_ear(Halfedge long_side);
  // polish()'s last repair of a triangle under a degree that fix_bad_faces could not remove
  // (degenerate.cpp); on while merge_flat_across_features is set.
  bool collapse_flat_across_features(const Halfedge sides[3]);
  bool merge_flat_across_features = false;
  bool is_zero_area(mesh::Face f) const;
  Halfedge longest_side(mesh::Face f, bool* needle, Halfedge* shortest) const;
  bool repair_flip_ok(Edge e) const;

  // ---- the reference decides where the surface strays from it (fidelity.cpp)
  // An edge strays when its midpoint is farther than kFidelityMidpoint x the tolerance from the
  // reference, or a quarter point farther than kFidelityQuarter x it. Where the sizing is right
  // the check must not fire: an edge at the split threshold (4/3 L) of a sphere sized by the
  // paper's formula is 4/3 epsilon off at its midpoint and 1 epsilon at its quarter points (at 1.0
  // for both, the sphere's edges came out 20 % short). Where a chord passes over a crease, its
  // distance from the surface peaks there, at t along it, and falls linearly to both ends: the
  // two limits bound the peak by 1.7 tolerances wherever t is (at t = 0.41), under the target's 2.
  static constexpr double kFidelityMidpoint = 1.4;
  static constexpr double kFidelityQuarter = 1.05;
  // The other side (flip_keeps_fidelity, collapse_keeps_fidelity): a point of the surface an
  // operation removes stays within this many tolerances of the triangles that replace it, the
  // Hausdorff target. At kFidelityMidpoint a sphere's collapses were refused where the sizing asks
  // for them (its edges 14 % short of the paper's length, 11 % at 2 and above).
  static constexpr double kFidelityOtherSide = 2.0;
  std::vector<Vec3> ref_normal;  // per tree triangle: unit normal (zero when degenerate)
  void build_reference_normals();
  // Per reference point: the largest turn between two triangles of its fan, as 1 - cos (at most 2).
  std::vector<double> ref_star_turn;
  void build_reference_star_turns();
  // The one corner two reference triangles share, else (none, or an edge) UINT32_MAX.
  std::uint32_t shared_reference_corner(std::uint32_t t0, std::uint32_t t1) const;
  double fidelity_tolerance() const;  // the base the limits multiply; 0 when the check is off (uniform, regions)
  bool segment_strays(const Point& a, std::uint32_t hint_a, const Point& b, std::uint32_t hint_b,
                      double tolerance) const;
  // The largest squared distance from the reference of the quarter and middle points of v's edges,
  // v at p (hint: the reference triangle under p), measured.
  double fan_stray_peak2(Vertex v, const Point& p, std::uint32_t hint) const;
  bool edge_strays(Edge e, double tolerance) const;
  bool strays_at(const Point& p, std::uint32_t hint) const;
  size_t undo_straying_moves();  // after the guarded projection; see fidelity.cpp
  std::vector<Point> fidelity_old;             // its scratch, per vertex slot
  std::vector<std::uint8_t> fidelity_moved;    // 0 unmoved, 1 moved, 2 sent back, 3 kept (off its old place)
  std::vector<Vertex> fidelity_queue;
  bool fan_strays(Vertex v) const;  // an edge at v strays
  bool fan_strayed_at(Vertex v, const Point& p, std::uint32_t hint) const;  // the same with v at p
  void split_placed_on_reference(Edge e, const Point& mid);  // a fidelity split, checked
  // Whether splitting e at p turns none of its triangles' halves by more than acos(min_cos) from
  // the triangle it replaces and leaves none with a smallest angle's squared sine under min_sin2.
  bool split_halves_fair(Edge e, const Point& p, double min_cos, double min_sin2) const;
  Point place_on_reference(Edge e, const Point& mid) const;  // where a fidelity split puts its vertex  // p farther than fidelity_tolerance() from it
  // (tolerance_times: of fidelity_tolerance(); the sliver repair allows more)
  bool collapse_keeps_fidelity(Halfedge h, const Point& target, bool both_ends_move, double tolerance_times = 1.0) const;
  // The same against an absolute tolerance (> 0), whatever the mode (needs a current reference).
  bool collapse_stays_within(Halfedge h, const Point& target, bool both_ends_move, double tolerance) const;
  bool flip_keeps_fidelity(Edge e, double tolerance_times = 1.0) const;  // a flip of e (its new edge, its old one's midpoint)
  // Whether p lies within `limit` of one of `triangles` triangles, given as three corners each.
  bool near_triangles(const Point& p, const Point* corners, size_t triangles, double limit) const;

  // ---- the other side of the fidelity check (coverage.cpp): reference points the surface left
  // more than kCoverageLimit x the tolerance behind (a tip worn away iteration by iteration)
  // get a vertex back on them (a vertex moved there or an edge split there), anchored to them.
  // Returns the pins; *splits: how many split an edge. With may_split false (the last iterations
  // of a batch, where no later iteration rebuilds around a split), only a point farther than the
  // Hausdorff target (coverage.cpp: kLateSplitTolerances) may get a split, whose edges stay on the
  // reference.
  size_t cover_reference_points(bool may_split, size_t* splits);
  // An anchored vertex is never removed and moves only within the limit of its point, so that it
  // keeps the point covered; within that it moves like any free vertex (a corner that never
  // moved left 16-degree triangles around it on fandisk at the defaults).
  bool anchored(Vertex v) const { return anchor[v] != UINT32_MAX && fidelity_tolerance() > 0; }
  bool anchor_holds(Vertex v, const Point& p) const;
  // Whether a pin that cannot move a vertex may split an edge: not at all; as the iterations before
  // the last two do (a point's halves may stray from the reference: the iterations after rebuild
  // the worn tip); or late, only where no edge at the new vertex strays (none follow).
  enum class PinSplit { kNever, kAny, kLate };
  // 0: not pinned, 1: a vertex moved onto the point, 2: an edge split there.
  int pin_reference_point(std::uint32_t point, Face nearest, PinSplit split);
  bool move_onto_reference_point(Vertex w, std::uint32_t point);
  double reference_angle_deficit(std::uint32_t point) const;  // 2 pi - the angles at it (radians)
  // Sliver placement moves v only where it keeps covered every reference point near it that its
  // fan covered before the move, by that fan or a face next to it (the polish after the last
  // iteration wore a CAD part's edge 1.4 % of the diagonal off). note_cover_duty(v), with v at
  // its start: those points (the corners of v's and its ring's hint triangles covered by v's
  // fan) and their distances; move_keeps_cover(v, start): whether v where it is now covers them.
  struct CoverDuty {
    std::uint32_t point;
    double distance;
  };
  std::vector<CoverDuty> cover_duty;
  void note_cover_duty(Vertex v);
  bool move_keeps_cover(Vertex v, const Point& start) const;
  double fan_distance2(Vertex v, const Point& at, const Point& p) const;
  std::vector<Face> coverage_faces;
  struct Uncovered {
    double distance2;
    std::uint32_t point;
    Face nearest;
  };
  std::vector<Uncovered> uncovered;
  std::vector<std::uint8_t> point_covered;  // per tree point, this call
  std::vector<Face> covered_by;             // per covered tree point: a face within the limit (if known)
  std::vector<std::uint32_t> coverage_queue;
  Face a_face_at(Vertex v) const;
  double face_distance2(Face f, const Point& p) const;  // squared, from p to its closest point on f
  Face face_near_covering(const Point& p, Face f, double limit2) const;
  void spread_cover_over_reference(double limit2);
  // Points along the reference's creases, covered like its points (coverage.cpp): a crease cut
  // off between two reference points is invisible to a check of the points alone. Ids from
  // tree.points().size() on name them (anchor, pins); the cover_* accessors take either kind.
  struct CreaseSample {
    Point p;
    std::uint32_t triangle;  // a reference triangle at the crease (a vertex's projection hint)
    double sizing;           // the reference sizing there
  };
  std::vector<CreaseSample> crease_samples;
  // The creases sampled: the samples of one lie evenly along it (a + j / (count + 1) (b - a), j = 1
  // .. count, from crease_samples[first] on); the coverage check's quick pass finds those near a face
  // from the creases of its corners' hint triangles (creases_of_triangle: up to three per triangle,
  // each crease under both triangles at it).
  struct SampledCrease {
    std::uint32_t a, b;  // tree points
    std::uint32_t first, count;
  };
  std::vector<SampledCrease> sampled_creases;
  std::vector<std::uint32_t> creases_of_triangle_offset, creases_of_triangle;
  std::vector<std::uint8_t> sample_covered;  // per crease sample, this call
  bool crease_samples_due = true;  // set by build_reference: sampled at the next coverage check
  void sample_reference_creases();
  bool is_reference_segment(std::uint32_t a, std::uint32_t b) const;  // a feature or boundary edge of the reference
  const Point& cover_point(std::uint32_t id) const;
  std::uint32_t cover_triangle(std::uint32_t id) const;
  double cover_sizing(std::uint32_t id) const;
  bool anchored_near(const Point& p, double radius);
  // Whether an edge from p (on the reference, in triangle `hint`) to an end of e or a corner
  // opposite it would stray (segment_strays): a split of e at p, off the edge, before it is made.
  bool split_strays(Edge e, const Point& p, std::uint32_t hint) const;
  // Whether the centre of a face at w lies farther from the reference than an edge's midpoint may:
  // a fan whose edges all lie on the reference can still tent across an inner corner.
  bool fan_faces_stray(Vertex w) const;
  std::vector<Point> pinned_now;  // this call's pins: one per worn tip, not one per point of it
  // Where the sizing is right a reference point may lie farther from the surface than an edge's
  // midpoint does: at the centre of a triangle at the split threshold (4/3 L) of a sphere sized
  // by the paper's formula, 16/9 epsilon. Below that the check would fire on smooth surfaces
  // (an icosphere at 1.4 tolerances: edges 12 % short of the formula's).
  static constexpr double kCoverageLimit = 1.8;
  // The split pass splits edges longer than this many sizings (Botsch & Kobbelt): the longest edge
  // it leaves, which the crease samples also use as the reach of a chord across a crease.
  static constexpr double kSplitFactor = 4.0 / 3.0;
  double coverage_limit() const { return kCoverageLimit * fidelity_tolerance(); }

  // ---- passes (split_collapse.cpp, flip_relax.cpp)
  void gather_all_edges();
  size_t split_long_edges();
  bool refining_wholesale = false;  // (split_long_edges: the guard was off when it started)
  size_t collapse_short_edges();
  size_t flip_edges();
  size_t flip_for_angles(double poor_angle);
  void relax_vertices();
  size_t fix_bad_faces(double angle_deg);
  // Collapses that raise the smallest angle of triangles below angle_deg (angle_collapse.cpp).
  size_t collapse_for_angles(double angle_deg);
  // Moves the free corners of triangles under angle_deg, and in necks those of crossing
  // triangles, to better places on the reference (sliver.cpp); only in necks with necks_only.
  size_t place_sliver_vertices(double angle_deg, bool necks_only);

  // ---- mirror symmetry (mirror.cpp): see Remesher::enable_mirror
  int mirror_axis = -1;         // >= 0 while mirroring
  VertexProperty<Vertex> mirror;  // the image of each vertex while mirroring
  bool mirror_lent = false;       // its vector is the caller's (enable_mirror with a known map)
  // enable_mirror's checks and set-up with the map `image` (swapped in; on failure a lent map is
  // swapped back untouched). lent: the caller's map, sizes all 0 (between strokes).
  bool start_mirroring(int axis, std::vector<Vertex>& image, bool lent);
  void remove_mirror();  // mirroring off, enable_mirror's feature marks taken back
  // With features on, a lent map's feature pairs (an edge is a feature when its image is): the
  // edges unpaired at the last check (a feature whose image is no edge or no feature) and the
  // slots changed since are enough to find every unpaired one (mirror.cpp), while the marks are a
  // new remesher's (reset_slots) for this feature angle and plane.
  bool union_mirror_features(bool lent);
  void forget_mirror_pairs();
  void next_mirror_run();  // a new mark value in mirror_seen
  std::vector<Edge> mirror_unpaired;       // at the last check
  std::vector<Vertex> mirror_changed;      // slots changed since (note_mirror_changes)
  std::vector<std::uint32_t> mirror_seen;  // per vertex slot: mirror_run when listed
  std::uint32_t mirror_run = 0;
  bool mirror_pairs_known = false;
  double mirror_pairs_angle = 0;
  int mirror_pairs_axis = -1;
  std::vector<Vertex> mirror_ring;  // scratch: the changed slots' two rings and their images
  std::vector<Edge> mirror_candidates;
  std::vector<Vertex> near_scratch;
  Point mirrored(Point p) const {
    p[mirror_axis] = -p[mirror_axis];
    return p;
  }
  // The edge between the images of e's ends (e itself for an edge in or across the plane), or an
  // invalid handle if the mesh lost its symmetry (then mirroring stops: stop_mirroring()).
  Edge mirror_edge(Edge e);
  // Whether the vertices within one ring of a and b include the image of one of them: then an
  // operation on the edge (a, b) and the same on its image may interfere.
  bool overlaps_its_image(Vertex a, Vertex b);
  // For a flip of e (a, b with opposite c, d): the edge to flip with it (e itself when e is its
  // own image or when not mirroring), or an invalid handle when the two quads share a vertex
  // (flip neither).
  Edge flip_partner(Edge e);
  void stop_mirroring();
  void close_region_under_mirror(std::vector<Vertex>& region);
  void symmetrize_sizing(const std::vector<Vertex>& vertices);
  void symmetrize_positions();
  // Collapses h (midpoint: both ends meet in the middle) and, while mirroring, its image; returns
  // the number of collapses done (0 when the pair cannot be done symmetrically).
  size_t collapse_with_mirror(Halfedge h, bool midpoint);
  // Splits e at its midpoint and, while mirroring, its image at the image of that point, unless e
  // is no longer long (it was split as the image of an earlier edge); returns the splits done.
  // far_from_reference: split though not long (the fidelity check), if edge_strays still says so.
  size_t split_with_mirror(Edge e, bool far_from_reference = false);
  size_t split_shared_triangle(Edge e, Edge image);

  // ---- helpers
  double target_length(Edge e) const {
    return std::min(sizing[mesh.vertex(e, 0)], sizing[mesh.vertex(e, 1)]);
  }
  bool in_scope(Edge e) const {
    return scope[mesh.vertex(e, 0)] != kOutside && scope[mesh.vertex(e, 1)] != kOutside;
  }
  bool movable(Vertex v) const { return scope[v] == kActive && vclass[v] != kCorner; }
  // A flip of e changes the triangles of all four corners of its quad: none may be masked (the
  // sliver fix checks only e's ends otherwise, and flips next to a region's outside vertices).
  bool flip_spares_masked(Edge e) const {
    const Halfedge h = mesh.halfedge(e, 0), o = mesh.halfedge(e, 1);
    return !masked(mesh.to_vertex(mesh.next(h))) && !masked(mesh.to_vertex(mesh.next(o)));
  }
  bool is_feature(Edge e) const { return feature[e] != 0; }
  bool collapse_allowed(Halfedge h) const;
  bool collapse_topology_ok(Halfedge h) const;
  // collapse_for_angles' exceptions to the feature rules (angle_collapse.cpp): a line's end onto the
  // line, and a line's detour around one triangle onto the triangle's third side.
  bool line_end_collapse_ok(Halfedge h) const;
  bool line_detour_collapse_ok(Halfedge h) const;
  Halfedge line_end_edge(Vertex v) const;  // v's one feature edge, outgoing; invalid if not one
  // How far from the reference the collapses that merge feature lines may take the surface (degenerate.cpp).
  double feature_merge_tolerance() const;
  // min_cos: how far a surviving triangle's normal may turn (0.5 = 60 degrees).
  // check_reference_lines: also collapse_stays_near_reference (off only for
  // collapse_flat_across_features, which checks the surface's distance itself).
  bool collapse_geometry_ok(Halfedge h, const Point& target, bool both_ends_move, bool check_lengths = true,
                            double min_cos = 0.5, bool check_reference_lines = true) const;
  double collapse_quality(Halfedge h) const;
  // The smallest angle (squared sine) of the triangles around v with v moved to `at`, leaving out
  // those with the corner `skip` (the ones a collapse towards it removes; none when invalid).
  double fan_min_angle_sin2(Vertex v, const Point& at, Vertex skip) const;
  // ---- safety guards (safety.cpp)
  // v's fan: twice its area-weighted normal (not normalised), and whether two neighbouring
  // triangles (or the last and first) turn by more than acos(kCreaseCos): v sits on a sharp edge,
  // marked as a feature or not.
  struct FanShape {
    Vec3 normal;
    bool creased;
  };
  static constexpr double kCreaseCos = 0.7;
  FanShape fan_shape(Vertex v) const;
  // The crease test of fan_shape, fed one face normal at a time in fan order.
  struct FanCreaseTest {
    Vec3 first{0.0}, previous{0.0};
    double first2 = 0, previous2 = 0;
    bool turned = false;
    static bool turns(const Vec3& a, double a2, const Vec3& b, double b2) {
      // The angle exceeds acos(kCreaseCos) when the dot product is below kCreaseCos x both
      // lengths: negative, or its square below kCreaseCos^2 x both squared lengths.
      const double d = glm::dot(a, b);
      return d < 0 || d * d < kCreaseCos * kCreaseCos * a2 * b2;
    }
    void add(const Vec3& n) {
      const double n2 = glm::dot(n, n);
      if (!(n2 > 0)) return;
      if (previous2 > 0 && turns(n, n2, previous, previous2)) turned = true;
      if (first2 == 0) first = n, first2 = n2;
      previous = n, previous2 = n2;
    }
    void gap() { previous2 = 0; }  // a boundary: the faces on its two sides are not neighbours
    bool creased() const { return turned || (previous2 > 0 && first2 > 0 && turns(first, first2, previous, previous2)); }
  };
  // How far from the reference surface an operation may take the mesh at a sharp edge: epsilon
  // (adaptive), kToleranceTargetLengths x the target length (uniform), times tolerance_scale. But
  // no less than kToleranceMinLengths x min_length: edges that long (the clamp, where the field
  // asks for shorter ones) cut a sharp edge by up to half their length whatever the guards do,
  // and holding vertices to a tighter bound there only leaves poor triangles (dragon at the
  // default epsilon 0.05 % and min length 0.2 %: 0.071 % of its triangles under 30 degrees at
  // epsilon, 0.037 % at the min length's half, 0.025 % without guards).
  static constexpr double kToleranceTargetLengths = 0.25;
  static constexpr double kToleranceMinLengths = 0.5;
  double surface_tolerance() const;
  // Scales the tolerance: the input's clean-up of degenerate triangles (Remesher::iterate) is
  // meant to remove zero-area triangles, not to reshape: it runs with kCleanupTolerance.
  double tolerance_scale = 1.0;
  static constexpr double kCleanupTolerance = 0.1;
  // Whether collapsing h with its moving end(s) at `target` keeps the mesh within the tolerance
  // of the reference at sharp edges (true without a current reference).
  bool collapse_stays_near_reference(Halfedge h, const Point& target, bool both_ends_move) const;
  // The projection of a whole-mesh iteration, with a guard: a free vertex on a sharp edge whose
  // relaxation left the place where it was farther than the tolerance from its new fan goes back
  // (relaxed_from: per scope vertex, its position before the relaxation). Returns those undone.
  std::vector<Point> relaxed_from;
  std::vector<std::uint32_t> creased_moved;  // scratch: scope indices
  // With keep_fan_shapes, relax_vertices leaves each free vertex's fan shape (before its move)
  // in fan_shapes, per scope vertex, measured on the face terms it computes anyway.
  bool keep_fan_shapes = false;
  std::vector<FanShape> fan_shapes;
  void remember_positions();
  size_t project_vertices_guarded();
  // ---- no new self-intersections (crossing_guard.h). A region iteration's guard holds the
  // region's faces and the ring around them (region_faces.cpp, region_guard.cpp).
  mutable CrossingGuard crossing_guard;  // (its tests keep scratch)
  std::vector<Point> before_move;        // per vertex slot: relaxed_from, for undo_crossing_moves
  void start_crossing_guard() {
    if (whole_mesh) {
      crossing_guard.resume(mesh);
      return;
    }
    if (!region_crossing_guard) return;
    collect_region_faces();
    crossing_guard.start_region(mesh, region_faces);
  }
  // Remesher::set_region_crossing_guard. Off by default: the dragon pull's frames cost 1.6x
  // (median) to 2.8x (max) the instructions with it (region_guard.cpp), above issue 18's budget.
  bool region_crossing_guard = false;
  Remesher::RegionWatch region_watch;
  // The faces of the scope's vertices and those of their neighbours outside it: every face a
  // region operation rewrites, and the ring next to the triangles it creates.
  std::vector<Face> region_faces;
  std::vector<std::uint8_t> region_face_listed;  // per face slot, all 0 between calls
  std::vector<std::uint32_t> scope_at;           // per vertex slot: its index in scope_vertices (when it is there)
  void collect_region_faces();
  void undo_region_crossing_moves();
  // Batch use (Remesher::keep_guard_grid): the grid lives from one call to the next, suspended,
  // unless the next whole-mesh split pass is expected to split more than one edge per this many
  // faces (expected_splits: the last pass's count, unknown before the first; see run_iteration).
  bool keep_guard_grid = false;
  static constexpr size_t kSplitsPerFaceToRebuild = 8;
  size_t expected_splits = SIZE_MAX;
  void end_crossing_guard() {
    if (keep_guard_grid)
      crossing_guard.suspend(mesh);
    else
      crossing_guard.stop();
  }
  bool collapse_crosses(Halfedge h, const Point& target, bool both_ends_move) const {
    return crossing_guard.collapse_crosses(mesh, h, target, both_ends_move);
  }
  void note_fan_changed(Vertex v) { crossing_guard.fan_changed(mesh, v); }
  // After relaxation and projection: the moved vertices whose fans cross go back.
  void undo_crossing_moves();
  // Picks how to collapse the short edge e (ratio: squared length / squared threshold): the
  // halfedge and whether both ends meet at the midpoint; false when no collapse is allowed.
  bool choose_collapse(Edge e, double ratio, Halfedge* h, bool* midpoint) const;
  void apply_collapse(Halfedge h, bool midpoint);
  bool flip_geometry_ok(Edge e, bool require_flat) const;
  bool flip_topology_ok(Edge e) const;  // needs `valence` current (flip passes)
  // Flips e and keeps `valence` and `valence_excess` of its quad's corners up to date.
  void flip_counting(Edge e);
  Vertex split_edge(Edge e, const Point& p);
  IterationStats run_iteration(bool project);
};

}  // namespace adasculpt::remesh
