#pragma once
// Brush strokes with dynamic topology: the pointer path is cut into stamps every
// spacing * radius of travel; each stamp (and its mirror image when symmetry is on) is one
// deformation step (deform/brushes.h) followed by ONE local remeshing iteration on the brushed
// vertices plus a ring, the same interleaving as a grab frame (PAPER.md section 4).
//
// Nothing global happens per stamp: the stamp's vertex is found by walking from the previous
// stamp's vertex (a stroke's first stamp walks from the last stroke's, and scans the surface only
// when that walk does not reach the point), and the mesh is
// not garbage-collected during the stroke (the Session compacts it afterwards when deleted slots
// add up).
#include <functional>
#include <vector>

#include "deform/brushes.h"
#include "mesh/surface_mesh.h"

namespace adasculpt::remesh {
class Remesher;
}

namespace adasculpt::sculpt {

// A whole stroke, as in session files: {"brush": {"tool": ..., "path": [...], "radius": r, ...}}.
struct BrushStroke {
  deform::BrushSettings settings;
  std::vector<Point> path;
  std::vector<double> pressure;  // one per path point, or empty (= 1)
};

// What the stamps of one sample() cost and changed.
struct BrushFrame {
  int stamps = 0;
  double locate_ms = 0, deform_ms = 0, remesh_ms = 0;
  bool topology_changed = false;
  bool limit_reached = false;  // this sample found the stroke's face budget spent (see kStrokeFaceBudget...)
  std::vector<mesh::Vertex> touched;  // brushed vertices + ring after remeshing, appended per stamp
};

// How much one stroke may grow the mesh. A stroke whose displacement per stamp is many edge lengths
// (a large inflate on a finely remeshed surface) can crumple the surface faster than relaxation
// irons it out; the adaptive sizing then refines every fold and each stamp doubles its region, so
// without a bound one stroke went from 37k to 3 million vertices and never finished. Past the
// budget the stroke stops stamping (the mesh stays valid and the stroke is one undo step); the
// Session reports it once. Budget: 4x the faces at the stroke's start, at least 250k faces, and
// no more than 3M faces (the browser's 2 GB heap holds about 3.6M with history) unless the mesh
// already has more, in which case it may not grow.
constexpr size_t kStrokeGrowthFactor = 4;
constexpr size_t kStrokeFaceFloor = 250000;
constexpr size_t kStrokeFaceCeiling = 3000000;
size_t stroke_face_budget(size_t faces_at_start);

// The surface point nearest p (*on_surface) and the vertex nearest that point: a scan of the
// vertices, and of the faces only when p is not on the surface around the nearest vertex (the
// stroke's own start, and a grab's press: an AABB tree of the whole surface took 1 s to build at
// 2M triangles, for one closest point). Throws std::invalid_argument when the mesh has no face.
mesh::Vertex locate_on_surface(const mesh::SurfaceMesh& mesh, const Point& p, Point* on_surface);

class BrushStroker {
 public:
  void begin(const deform::BrushSettings& settings);
  // One pointer sample. The first sample of a stroke stamps at once (grab: only picks up the
  // surface there); later ones stamp every spacing * radius along the segment from the previous
  // sample, with the pressure interpolated. Appends to `frame`.
  void sample(mesh::SurfaceMesh& mesh, remesh::Remesher& remesher, const Point& p, double pressure, BrushFrame& frame);
  bool started() const { return started_; }
  bool limit_reached() const { return limit_reached_; }
  size_t face_budget() const { return face_budget_; }
  const deform::BrushSettings& settings() const { return settings_; }
  deform::BrushDeformer& deformer() { return deformer_; }
  // Called once per stroke when its first sample has found the surface, before the first stamp:
  // the vertex there, and whether it was reached by walking from the last stroke's (then it lies
  // on the same connected component). The Session sets the stroke's detail there.
  using StartHook = std::function<void(const mesh::SurfaceMesh&, mesh::Vertex, bool walked)>;
  void set_start_hook(StartHook hook) { start_hook_ = std::move(hook); }
  // Finds the surface under a stroke's first sample when the walk from the last stroke's vertex
  // does not reach it (and a mirrored start without the remesher's pairing): the vertex there and
  // the surface point (*on_surface). Without one, locate_on_surface (a scan of the mesh: 90 ms at
  // 1.1M triangles); the Session gives a query of its slot tree, which follows the changes.
  using Locator = std::function<mesh::Vertex(const mesh::SurfaceMesh&, const Point&, Point* on_surface)>;
  void set_locator(Locator locator) { locator_ = std::move(locator); }
  // Starts the remesher's mirroring for a symmetric stroke and says whether it runs. Without one,
  // Remesher::enable_mirror searches the whole mesh for the map; the Session lends the map it
  // keeps up to date through every change (geometry::MirrorTracker).
  using MirrorStart = std::function<bool(const mesh::SurfaceMesh&, remesh::Remesher&, int axis)>;
  void set_mirror_start(MirrorStart start) { mirror_start_ = std::move(start); }

 private:
  void stamp(mesh::SurfaceMesh& mesh, remesh::Remesher& remesher, const Point& target, double pressure, BrushFrame& f);
  mesh::Vertex reseed(const mesh::SurfaceMesh& mesh, mesh::Vertex seed, const Point& target) const;
  Point mirror(Point p) const {
    p[settings_.symmetry_axis] = -p[settings_.symmetry_axis];
    return p;
  }
  bool symmetric() const { return settings_.symmetry_axis >= 0; }

  deform::BrushSettings settings_;
  deform::BrushDeformer deformer_;
  bool started_ = false;
  bool limit_reached_ = false;
  size_t face_budget_ = 0;
  Point last_sample_{0.0};
  double last_pressure_ = 1;
  double travelled_ = 0;  // path length since the last stamp
  mesh::Vertex seed_, mirror_seed_;
  Point grab_centre_{0.0};  // grab: the surface point being dragged (moves with the pointer)
  Point grab_target_{0.0};  // grab: the path point of the last stamp
  std::vector<mesh::Vertex> last_region_;  // for re-seeding when a seed was collapsed away
  mesh::Vertex last_stroke_seed_;
  StartHook start_hook_;  // where the last stamp was: the next stroke's start walks from it
  Locator locator_;
  MirrorStart mirror_start_;
};

}  // namespace adasculpt::sculpt
