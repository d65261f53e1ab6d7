#include "remesh/remesher.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "geometry/topology.h"
#include "mesh/scratch.h"
#include "remesh/remesher_impl.h"
#include "remesh/sizing.h"

namespace adasculpt::remesh {

namespace {
// Pairs of triangles with an angle below this get a Delaunay flip when it helps (beyond the
// paper, which flips for valence only): measured on the shared meshes it lifts the minimum
// angle by 2-5 degrees at no visible cost in valence regularity.
constexpr double kPoorAngleDeg = 30.0;
// Input triangles below this angle are degenerate: removed before the first iteration.
constexpr double kDegenerateAngleDeg = 1.0;
// Triangles below this angle after an iteration get a dedicated collapse or flip.
constexpr double kSliverAngleDeg = 12.0;
// Triangles below this angle get their corners moved (sliver.cpp): in necks after each
// whole-mesh iteration, anywhere once the iterations are done (Remesher::polish).
constexpr double kPlacedSliverAngleDeg = 25.0;
// Triangles still below this angle when a batch remesh ends get a collapse that improves them
// (angle_collapse.cpp): issue 17's minimum-angle target.
constexpr double kTargetAngleDeg = 20.0;
// Region iterations between two measurements of the sizing field (see iterate_region).
constexpr int kRegionSizingInterval = 4;
// A scope this large (a grab's ROI) measures a slice of itself in every call instead, the whole
// scope over kRegionSizingInterval calls: measuring a 10k-vertex region at once (20-26M
// instructions) made every 4th frame of a pull 1.5x the others, a quarter of the frames.
constexpr size_t kSpreadSizingFrom = 4096;
// A batch remesh puts the mesh in space order after an iteration that appended more than one
// new face slot per this many live faces (remesh()).
constexpr size_t kNewSlotsToSort = 4;
}  // namespace

double bounding_box_diagonal(const SurfaceMesh& mesh) { return geometry::bounding_box_diagonal(mesh); }

RemeshOptions default_options_for(const SurfaceMesh& mesh) {
  const double d = bounding_box_diagonal(mesh);
  RemeshOptions o;
  o.epsilon = kDefaultEpsilonPct * 0.01 * d;
  o.min_length = kDefaultMinLengthPct * 0.01 * d;
  o.max_length = kDefaultMaxLengthPct * 0.01 * d;
  o.target_length = kDefaultTargetLengthPct * 0.01 * d;
  return o;
}

void check_options(const RemeshOptions& o) {
  auto positive = [](double x, const char* name) {
    if (!(x > 0) || !std::isfinite(x)) throw std::invalid_argument(std::string(name) + " must be a positive number");
  };
  if (o.adaptive) {
    positive(o.epsilon, "epsilon");
    positive(o.min_length, "min-length");
    positive(o.max_length, "max-length");
    if (o.min_length > o.max_length)
      throw std::invalid_argument("min-length (" + std::to_string(o.min_length) + ") is larger than max-length (" +
                                  std::to_string(o.max_length) + ")");
  } else {
    positive(o.target_length, "length");
  }
  if (o.iterations < 0) throw std::invalid_argument("iterations must not be negative");
  if (o.max_vertices < 4) throw std::invalid_argument("max-vertices must be at least 4");
  if (!(o.feature_angle_deg >= 0 && o.feature_angle_deg <= 180))
    throw std::invalid_argument("features must be an angle between 0 and 180 degrees");
}

Remesher::Remesher(SurfaceMesh& mesh, const RemeshOptions& options) : impl_(std::make_unique<Impl>(mesh, options)) {
  check_options(options);
  impl_->reference_stale = true;
}

Remesher::~Remesher() {
  impl_->mirror_marked.clear();  // the marks go with the remesher (the mesh may be another one by now)
  disable_mirror();              // the map is only valid while the remesher keeps it
}

const RemeshOptions& Remesher::options() const { return impl_->opt; }

const RemeshReport& Remesher::report() const { return impl_->report; }

void Remesher::set_options(const RemeshOptions& options) {
  check_options(options);
  bool features_changed = options.feature_angle_deg != impl_->opt.feature_angle_deg;
  impl_->opt = options;
  if (features_changed) {
    for (Edge e : impl_->mesh.edges()) impl_->feature[e] = 0;
    impl_->mark_features();
  }
  impl_->reference_stale = true;
}

void Remesher::reset_reference() { impl_->reference_stale = true; }
void Remesher::log_deleted_faces(std::vector<Face>* log) { impl_->deleted_faces_log = log; }

void Remesher::reserve_scratch() {
  Impl& m = *impl_;
  const size_t nv = m.mesh.vertices_size(), nf = m.mesh.faces_size();
  mesh::resize_scratch(m.face_quality, nf);
  mesh::resize_scratch(m.face_seen, nf, 0u);
  mesh::resize_scratch(m.relax_faces, nf);
  mesh::resize_scratch(m.valence, nv);
  mesh::resize_scratch(m.valence_excess, nv);
  mesh::resize_scratch(m.kappa, nv);
  mesh::resize_scratch(m.kappa_known, nv, std::uint8_t(0));
  if (m.region_crossing_guard) {  // (its per-slot arrays: none while it is off)
    mesh::resize_scratch(m.region_face_listed, nf, std::uint8_t(0));
    mesh::resize_scratch(m.scope_at, nv);
    m.crossing_guard.reserve_region(m.mesh);
  }
}

IterationStats Remesher::Impl::run_iteration(bool do_project) {
  IterationStats stats;
  // A kept grid must follow the splits (they report their fans, and while it is on each is
  // checked: split_with_mirror), but when the split pass refines the mesh wholesale, as the
  // first one mostly does (dragon.off: 60k
  // splits on 100k faces, 207k at epsilon 0.01 %; bunny.off 4,940 on 70k), a build after the
  // splits costs less than inserting every new face (keeping it made the dragon at epsilon
  // 0.01 % 12 % slower and 9 % larger). Later passes split a few hundred edges. (The sizing
  // field's estimate of the output predicts the first pass badly: the dragon's grows by 14k
  // vertices through 60k splits and 44k collapses.) Checking the splits of every pass after the
  // first (the dragon's second, 1,794 splits, runs without the grid) was cheaper on the shared
  // meshes but put cgal/ChineseDragon-10kv at epsilon 0.01 %, features 45, from 8.8 s of CPU over
  // the sweep's 10 s cap: the long splits of a pass without the grid stay unchecked.
  if (keep_guard_grid && whole_mesh) {
    if (expected_splits < mesh.n_faces() / kSplitsPerFaceToRebuild)
      start_crossing_guard();
    else
      crossing_guard.stop();
  }
  stats.splits = split_long_edges();
  if (whole_mesh) expected_splits = stats.splits;
  start_crossing_guard();  // whole-mesh iterations: from here on no operation may cross the surface
  stats.collapses = collapse_short_edges();
  stats.flips = flip_edges();
  stats.flips += flip_for_angles(kPoorAngleDeg * M_PI / 180.0);
  const bool guarded = do_project && has_reference;
  if (guarded || whole_mesh || region_crossing_guard) remember_positions();  // (for undo_crossing_moves)
  keep_fan_shapes = guarded;
  relax_vertices();
  keep_fan_shapes = false;
  if (guarded) {
    project_vertices_guarded();
    undo_straying_moves();
    undo_line_slides(relaxed_from);
  }
  undo_crossing_moves();
  fix_bad_faces(kSliverAngleDeg);
  return stats;
}

IterationStats Remesher::iterate(bool late) {
  Impl& m = *impl_;
  if (m.reference_stale) {
    // Rebuilt lazily so that a series of edits between iterations costs one rebuild.
    m.enter_whole_mesh();
    // Before the reference: its tree and the curvature then see no zero-area triangles the
    // repairs could remove (they leave the surface as it is, so the reference loses nothing).
    m.remove_degenerate_faces();
    m.build_reference();
    m.start_crossing_guard();
    m.crossing_guard.contain_inherited_crossings(true);
    m.tolerance_scale = Impl::kCleanupTolerance;
    m.fix_bad_faces(kDegenerateAngleDeg);
    m.end_crossing_guard();
    m.tolerance_scale = 1.0;
  }
  m.enter_whole_mesh();  // (again after removing degenerate faces, which deletes vertices)
  m.reserve_for_splits();
  m.region_calls_since_sizing = 0;
  m.sizing_spread = false;
  // The warning speaks of the mesh as it is now: a split cascade the budget cut short in an early
  // iteration (needles of a coarse CAD input) that later iterations completed is no news.
  m.report.warning.clear();
  IterationStats stats = m.run_iteration(m.opt.projection);
  m.place_sliver_vertices(kPlacedSliverAngleDeg, true);
  stats.pins = m.cover_reference_points(!late, &stats.pin_splits);
  m.end_crossing_guard();
  m.leave_whole_mesh();
  return stats;
}

void Remesher::Impl::enter_whole_mesh() {
  scope_vertices.clear();
  mask = mesh::find_mask(mesh);
  const std::uint8_t* deleted = mesh.vertex_deleted_data();
  std::uint8_t* sc = scope.vector().data();
  const mesh::Index n = static_cast<mesh::Index>(mesh.vertices_size());
  for (mesh::Index i = 0; i < n; ++i)
    if (!deleted[i] && !masked(Vertex(i))) {
      sc[i] = kActive;
      scope_vertices.push_back(Vertex(i));
    }
  if (mask.is_valid()) hold_around_masked();
  whole_mesh = true;
}

void Remesher::Impl::hold_around_masked() {
  const auto* hc = mesh.halfedge_connectivity_data();
  const Halfedge* vh = mesh.vertex_halfedge_data();
  const std::uint8_t* deleted = mesh.vertex_deleted_data();
  std::uint8_t* sc = scope.vector().data();
  const mesh::Index n = static_cast<mesh::Index>(mesh.vertices_size());
  for (mesh::Index i = 0; i < n; ++i)
    if (!deleted[i] && masked(Vertex(i)))
      for_each_outgoing(hc, vh, Vertex(i), [&](Halfedge h) {
        std::uint8_t& s = sc[hc[h.idx].to.idx];
        if (s == kActive) s = kHeld;
      });
}

void Remesher::Impl::leave_whole_mesh() {
  const std::uint8_t* deleted = mesh.vertex_deleted_data();
  std::uint8_t* sc = scope.vector().data();
  const mesh::Index n = static_cast<mesh::Index>(mesh.vertices_size());
  for (mesh::Index i = 0; i < n; ++i)
    if (!deleted[i]) sc[i] = kOutside;
  whole_mesh = false;
}

IterationStats Remesher::iterate_region(std::vector<Vertex>& region) {
  Impl& m = *impl_;
  // The deformed surface is the reference now; the stored one is out of date.
  m.reference_stale = true;
  if (m.mirror_axis >= 0) m.close_region_under_mirror(region);
  m.scope_vertices.clear();
  m.mask = mesh::find_mask(m.mesh);
  for (Vertex v : region)
    if (!m.mesh.is_deleted(v) && m.scope[v] == kOutside && !m.masked(v)) {
      m.scope[v] = kActive;
      m.scope_vertices.push_back(v);
    }
  // Vertices with a neighbour outside the region hold the border in place, the feature
  // classification may be stale where the deformation added vertices, and the split pass needs
  // every edge of the scope (scope_edges): one walk around each fan does all three. Held
  // or active makes no difference to which edges are the scope's.
  {
    const auto* hc = m.mesh.halfedge_connectivity_data();
    const Halfedge* vh = m.mesh.vertex_halfedge_data();
    const std::uint8_t* feat = m.feature.vector().data();
    std::uint8_t* sc = m.scope.vector().data();
    m.scope_edges.clear();
    for (Vertex v : m.scope_vertices) {
      int features = 0;
      bool held = false;
      for_each_outgoing(hc, vh, v, [&](Halfedge h) {
        const mesh::Index w = hc[h.idx].to.idx;
        const bool outside = sc[w] == kOutside;
        held = held || outside;
        features += feat[h.idx >> 1] != 0;
        if (!outside && v.idx < w) m.scope_edges.push_back(SurfaceMesh::edge(h));
      });
      if (held) sc[v.idx] = kHeld;
      m.vclass[v] = vertex_class(features);
    }
  }
  // The curvature of a surface being dragged changes little from one frame to the next: the
  // sizing is measured again every few calls, and vertices added in between carry the mean
  // of their edge's ends (split_edge).
  // A region that moves (a brush stroke) brings in vertices never measured (sizing 0, every
  // measured value is at least min_length): with a zero target every edge there would be split
  // again and again. Measure at once when one is in the scope.
  // A large scope measures its slice and its few unmeasured vertices (a grab's refinement adds
  // some every frame); the whole scope only when many are unmeasured (a fresh remesher).
  m.sizing_slice.clear();
  for (Vertex v : m.scope_vertices)
    if (!(m.sizing[v] > 0)) m.sizing_slice.push_back(v);
  const size_t n = m.scope_vertices.size(), unmeasured = m.sizing_slice.size();
  m.sizing_spread = n >= kSpreadSizingFrom && unmeasured < n / kRegionSizingInterval;
  if (m.sizing_spread) {
    // The slice: a contiguous part of the scope (a grab lists its region by geodesic distance, so
    // a ring of it), the gradation limited within it as a whole measurement limits the scope.
    const size_t k = size_t(m.region_calls_since_sizing);
    for (size_t i = n * k / kRegionSizingInterval; i < n * (k + 1) / kRegionSizingInterval; ++i)
      if (m.sizing[m.scope_vertices[i]] > 0) m.sizing_slice.push_back(m.scope_vertices[i]);
    m.compute_sizing_from_current_surface(m.sizing_slice);
    // The slice's new values meet those the rest of the scope got in other frames: the gradation
    // limit over the whole scope (on a graded field only vertices that lower a neighbour start
    // its queue: cheap). Without it the held-out pull's worst triangle fell from 25 to 19 degrees.
    mesh::resize_scratch(m.kappa_known, m.mesh.vertices_size(), std::uint8_t(0));
    for (Vertex v : m.scope_vertices) m.kappa_known[v.idx] = 1;
    limit_sizing_gradation(m.mesh, m.scope_vertices, m.sizing, kGradation, &m.kappa_known);
    for (Vertex v : m.scope_vertices) m.kappa_known[v.idx] = 0;
  } else if (m.region_calls_since_sizing == 0 || unmeasured) {
    m.compute_sizing_from_current_surface(m.scope_vertices);
  }
  m.region_calls_since_sizing = (m.region_calls_since_sizing + 1) % kRegionSizingInterval;
  if (m.region_watch) m.region_watch(m.mesh, false);
  IterationStats stats = m.run_iteration(false);
  m.crossing_guard.stop();
  if (m.region_watch) m.region_watch(m.mesh, true);
  region.clear();
  for (Vertex v : m.scope_vertices)
    if (!m.mesh.is_deleted(v)) {
      m.scope[v] = kOutside;
      region.push_back(v);
    }
  return stats;
}

void Remesher::set_region_crossing_guard(bool on) { impl_->region_crossing_guard = on; }
void Remesher::watch_region_iterations(RegionWatch watch) { impl_->region_watch = std::move(watch); }

void Remesher::keep_guard_grid() { impl_->keep_guard_grid = true; }

Remesher::Tidied Remesher::tidy_between_iterations(size_t& ordered_slots) {
  SurfaceMesh& mesh = impl_->mesh;
  // Splits append their elements at the end of the arrays, so after a pass that refines much
  // of the mesh (most first iterations) a fan's vertices, edges and faces lie far apart in
  // memory and every walk around a fan misses the cache. The next passes read the mesh in
  // space order instead: cgal/armadillo.off at epsilon 0.01 % / min length 0.02 % (100k ->
  // 146k vertices) took 11.1 s of CPU and 317 MB, now 8.0 s and 283 MB (a busy machine; CGAL's
  // ChineseDragon-10kv, bull and cheese gain 19-30 % too, docs/figures.md).
  if (mesh.faces_size() > ordered_slots + mesh.n_faces() / kNewSlotsToSort) {
    impl_->crossing_guard.stop();  // (its grid names faces by their old slots)
    mesh.sort_in_space();
    ordered_slots = mesh.faces_size();
    return Tidied::kSorted;
  }
  // Collapses only mark elements deleted and splits append new ones, so without compaction the
  // slots pile up over the iterations: cheese.off at --uniform --length 1% held 594k face slots
  // for 113k live faces, and every per-slot array (the mesh's, the passes' scratch, the crossing
  // guard's grid) was sized to the slots. Compacting (or sorting) here is safe: a batch remesher
  // has no mirror map and no face log, the only handles into the mesh that outlive an
  // iteration, and its per-element state lives in mesh properties, which follow. Only once the
  // deleted slots outnumber the live ones: compaction reorders the elements, and with them the
  // order the passes visit them in, which changes the result a little. (The kept grid sees the
  // new slot count and is built again, CrossingGuard::resume.)
  if (mesh.faces_size() > 2 * mesh.n_faces()) {
    mesh.garbage_collection();
    ordered_slots = mesh.faces_size();
    return Tidied::kCompacted;
  }
  return Tidied::kNothing;
}

bool Remesher::sizing_due() const { return impl_->region_calls_since_sizing == 0 && !impl_->sizing_spread; }

size_t Remesher::polish() {
  Impl& m = *impl_;
  m.enter_whole_mesh();
  m.start_crossing_guard();
  const size_t moved = m.place_sliver_vertices(kPlacedSliverAngleDeg, false);
  m.collapse_for_angles(kTargetAngleDeg);
  // The last iteration's sliver repair ran before its pins (cover_reference_points) and the
  // moves above, which can leave a vertex on the line through the other two corners of a
  // triangle (cgal/boeing.off at epsilon 0.5 %, once the strips between its panels' creases were
  // refined: a 0.00-degree triangle between two border vertices, which a collapse or a flip
  // removes). The same repair, guarded as there, for what is still under a degree.
  // Last, what that leaves: a strip with no area between two feature lines laid on one line
  // (degenerate.cpp, collapse_flat_across_features).
  m.merge_flat_across_features = true;
  m.fix_bad_faces(kDegenerateAngleDeg);
  m.merge_flat_across_features = false;
  m.crossing_guard.stop();
  m.leave_whole_mesh();
  return moved;
}

RemeshReport remesh(SurfaceMesh& mesh, const RemeshOptions& options) {
  RemeshReport report;
  {
    Remesher remesher(mesh, options);
    remesher.keep_guard_grid();  // nothing else edits the mesh here (but the compaction, allowed)
    size_t ordered_slots = mesh.faces_size();
    for (int i = 0; i < options.iterations; ++i) {
      remesher.iterate(/*late=*/i + 2 >= options.iterations);
      remesher.tidy_between_iterations(ordered_slots);
    }
    remesher.polish();
    report = remesher.report();
  }
  mesh.garbage_collection();
  return report;
}

}  // namespace adasculpt::remesh
