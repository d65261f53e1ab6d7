#pragma once
// Curvature-adaptive isotropic remeshing (Dunyach et al. 2013, sections 2-3) and the uniform
// remeshing of Botsch & Kobbelt 2004 it extends.
//
// One iteration = split long edges, collapse short ones, flip towards valence 6 (4 on the
// boundary), tangential relaxation weighted by area x sizing (paper eq. 6), projection back
// onto the reference surface. Target lengths come from the sizing field
// L = sqrt(6 eps / kappa - 3 eps^2) clamped to [min_length, max_length].
//
// A Remesher keeps its reference surface (AABB tree, curvature, sizing) alive between calls so
// that interactive use pays only for what changed; remesh() is the one-shot batch entry.
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mesh/surface_mesh.h"

namespace adasculpt::remesh {

using mesh::Face;
using mesh::SurfaceMesh;
using mesh::Vertex;

struct RemeshOptions {
  bool adaptive = true;
  double epsilon = 0.0;        // approximation tolerance (absolute length), adaptive mode
  double min_length = 0.0;     // sizing clamp (absolute), adaptive mode
  double max_length = 0.0;
  double target_length = 0.0;  // uniform mode
  int iterations = 5;
  bool projection = true;        // back-project onto the reference surface
  double feature_angle_deg = 0;  // > 0: edges with a larger dihedral angle are kept sharp
  // Hard limit on the vertices a whole-mesh remesh may hold at any time, whatever the settings ask
  // for: a remesh's peak memory is about 1.7 kB per vertex of its budget (the mesh, the passes'
  // buffers and the crossing guard's grid: 721 MB of heap for cheese.off's 441k), so the default
  // stays under the 1 GB the sweep allows a run and far under the browser tab's 2 GB.
  size_t max_vertices = kDefaultMaxVertices;
  static constexpr size_t kDefaultMaxVertices = 500'000;
};

// The one place the default lengths live, in percent of the bounding-box diagonal: the command
// line, a new sculpt::Session and (through the wasm module's defaultSettings()) the web app use them.
inline constexpr double kDefaultEpsilonPct = 0.05;
inline constexpr double kDefaultMinLengthPct = 0.2;
inline constexpr double kDefaultMaxLengthPct = 5;
inline constexpr double kDefaultTargetLengthPct = 1;  // uniform mode
// The defaults above as absolute lengths for this mesh.
RemeshOptions default_options_for(const SurfaceMesh& mesh);
double bounding_box_diagonal(const SurfaceMesh& mesh);

// Throws std::invalid_argument with a message a user can act on (epsilon <= 0, min > max...).
void check_options(const RemeshOptions& options);

struct IterationStats {
  size_t splits = 0, collapses = 0, flips = 0;
  // Whole-mesh adaptive iterations: vertices put back on reference points the surface had left
  // (coverage.cpp), and how many of them were new (an edge split there; the others moved there).
  size_t pins = 0, pin_splits = 0;
};

// What a whole-mesh remesh did beyond the mesh itself.
struct RemeshReport {
  // Vertices the sizing field asks for (its integral of 2 / (sqrt(3) L^2) over the input, the
  // vertex density of equilateral triangles of side L); 0 before the reference is built.
  double estimated_vertices = 0;
  // The vertex budget: 4 x estimate (at most 2 x estimate + 20,000) + the input's vertices + 1,000,
  // capped at options.max_vertices (budget.cpp).
  size_t vertex_budget = 0;
  // Empty, or one line for the user: in the last iteration the mesh hit its budget and splitting
  // stopped (the result is the valid mesh reached so far).
  std::string warning;
};

class Remesher {
 public:
  // The mesh's current surface becomes the reference for projection and sizing.
  // Marks feature edges when options.feature_angle_deg > 0. The remesher attaches its arrays
  // ("remesh:..." properties) to the mesh and removes them when it is destroyed, so one mesh has
  // at most one live Remesher at a time (destroy the old one before making the next).
  Remesher(SurfaceMesh& mesh, const RemeshOptions& options);
  ~Remesher();
  Remesher(const Remesher&) = delete;
  Remesher& operator=(const Remesher&) = delete;

  // One iteration over the whole mesh (projection as in the options).
  // Adaptive: ends by putting vertices back on reference points the surface has left farther than
  // the tolerance allows (coverage.cpp; IterationStats::pins), by moving a vertex there or by
  // splitting an edge there. late: one of the last two iterations of a batch, where pins only
  // move vertices (the long edges to a split's vertex take two more iterations to reach fair
  // triangles).
  IterationStats iterate(bool late = false);
  // After the whole-mesh iterations: moves the corners of the triangles still under 25 degrees
  // that no collapse or flip could remove to better places on the reference surface, then
  // collapses or flips away the triangles still under a degree. Returns the number of vertices
  // moved (0 before the first iteration).
  size_t polish();
  // One iteration restricted to the given vertices: only edges with both ends in the set are
  // touched and vertices on the border of the set stay where they are. No projection; the
  // curvature and sizing are taken from the current surface (the sculpting frame).
  // The vertex list is updated in place: removed vertices leave, new vertices join.
  IterationStats iterate_region(std::vector<Vertex>& region);
  // On: no region operation creates a crossing of two triangles (region_guard.cpp). Off by
  // default (the region iterations as they were): a 10k-vertex pull's frames cost 1.6x the
  // instructions (median; 2.8x the largest) with it.
  void set_region_crossing_guard(bool on);
  // Called with the mesh right before (done false) and right after (done true) each region
  // iteration's passes: tests count the crossings an iteration creates (nullptr: none).
  using RegionWatch = std::function<void(const SurfaceMesh& mesh, bool done)>;
  void watch_region_iterations(RegionWatch watch);
  // The next iterate_region measures the sizing of its whole scope again (it does every few
  // calls; a large scope, measured a slice per call, never all at once once measured): a caller
  // with a frame budget can give that frame's other work less.
  bool sizing_due() const;
  // The mesh changed around `vertices` (duplicates and deleted ones allowed): a sequence of region
  // iterations ended (a stroke or a grab: their sizing, measured every few calls and kept per
  // vertex, goes back to unmeasured), or an undo or redo swapped their slots back (the remesher's
  // arrays are not in the history: those slots hold whatever they held). Their per-slot state goes
  // back to what a new Remesher gives them, and the feature and boundary marks and vertex classes
  // around them are derived again from the current surface (two rings), so that on every live
  // slot the remesher equals a new one made on this mesh with these options: what a stroke does
  // depends on the mesh only, and a session keeps one remesher instead of paying a new one's pass
  // over every edge. (The mask is the mesh's and looked up by every call.)
  void reset_slots(const std::vector<Vertex>& vertices);
  // Mirror symmetry for region iterations (brush strokes with symmetry on). When the mesh is
  // exactly symmetric across the plane where coordinate `axis` is 0 (geometry::find_mirror_map),
  // iterate_region does every split, collapse, flip and move on both vertices/edges of a mirror
  // pair at once (the decision taken once, the positions of one side copied mirrored to the
  // other), so the mesh stays exactly symmetric, vertex for vertex. An operation whose image
  // overlaps it near the plane, where doing both is not certain to stay valid, is left out.
  // Returns false, and leaves mirroring off, when the mesh is not exactly symmetric.
  bool enable_mirror(int axis);
  // As enable_mirror(axis), with the map known (geometry::MirrorTracker: what find_mirror_map
  // would give now, sized to the vertex slots), the mask (if any) known to be its own mirror image
  // under it, and the mesh between strokes (every sizing 0, as reset_slots leaves it): no search
  // and, with features off, no pass over the mesh.
  // The map is borrowed: moved in (`known_map` is left empty; the mesh's mirror array is made from
  // it, not filled) and handed back by disable_mirror(&known_map); false (feature marks not
  // symmetric) leaves it as it was.
  bool enable_mirror(int axis, std::vector<Vertex>& known_map);
  // The vertex slots a step, an undo or a redo changed (geometry::MirrorTracker's list): with
  // features on, enable_mirror(axis, known_map) rechecks the feature pairs only around these slots
  // and their images, and the edges it found unpaired last time, instead of every edge (a change
  // not noted here would leave its pairs unchecked).
  void note_mirror_changes(const std::vector<Vertex>& changed);
  // Tests: the feature edges the last enable_mirror with a known map found unpaired (features on),
  // nullptr when it has not run since the feature marks were last made over the whole mesh.
  const std::vector<mesh::Edge>* mirror_unpaired_features() const;
  // Mirroring ends (a stroke ends). give_back: a borrowed map goes back there, updated by the
  // passes' splits and collapses; the result says whether it is the mesh's map (the stroke
  // mirrored to its end, so the mesh changed only through mirrored stamps and passes, which keep
  // it exactly symmetric) or must be found again (symmetry was lost on the way).
  bool disable_mirror(std::vector<Vertex>* give_back = nullptr);
  // While mirroring: the vertex at v's mirror image (vertices the iterations add included),
  // indexed by vertex index; nullptr when mirroring is off.
  const std::vector<Vertex>* mirror_map() const;
  // The mesh changed outside the remesher's control (e.g. deformation or a new load):
  // the reference surface is rebuilt from the current mesh on the next whole-mesh iteration.
  void reset_reference();
  // Face slots deleted by collapses are appended to *log from now on (nullptr: not recorded).
  // A renderer keeping one triangle per face slot learns from it which slots to empty: the
  // deleted faces are out of the connectivity and not reachable from the vertices left.
  void log_deleted_faces(std::vector<mesh::Face>* log);
  // Sizes the per-slot scratch arrays of the region passes (face quality and marks, relaxation
  // terms, valences, curvature) to the mesh's slots now, zero-filled, so that a sculpting frame
  // touches only its region's entries: sized in the first frame that needs them, they cost a
  // stroke on 1.1M triangles tens of milliseconds of allocation and page faults (issue 18). A
  // session calls it with each new mesh; the arrays outlive the remesher (RemeshScratch). The
  // region crossing guard's arrays too, when it is on (set_region_crossing_guard first).
  void reserve_scratch();
  // Batch use (remesh()): the caller promises that between this remesher's calls nothing edits
  // the mesh but a garbage collection. The crossing guard's grid then lives from one iterate() to
  // the next (and into polish()) instead of being built twice per iteration (but after a split
  // pass that refines wholesale, see run_iteration). Not for sessions: a stroke's edits would
  // leave the grid out of date.
  void keep_guard_grid();
  // Batch use, between two iterate() calls: puts the mesh in space order after an iteration
  // that appended many elements, or compacts it when deleted slots pile up (the kept grid follows
  // either). `ordered_slots`: the caller's record of the mesh's face slots when it was last in
  // order, the mesh's faces_size() before the first call.
  enum class Tidied { kNothing, kSorted, kCompacted };
  Tidied tidy_between_iterations(size_t& ordered_slots);
  // Estimate and budget since the reference was built, warning of the last whole-mesh iteration.
  const RemeshReport& report() const;
  const RemeshOptions& options() const;
  void set_options(const RemeshOptions& options);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Batch remeshing: options.iterations iterations against the input surface. Bounded: the mesh
// never exceeds the report's vertex budget, and the work of every pass is proportional to it.
RemeshReport remesh(SurfaceMesh& mesh, const RemeshOptions& options);

}  // namespace adasculpt::remesh
