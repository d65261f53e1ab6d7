#pragma once
// No operation of a whole-mesh remeshing iteration may make the surface cross itself (issue 17
// item 2). The per-face orientation tests of the passes only look at the one-ring: a collapse on
// one side of a thin part (a dragon's fin, a CAD part's coarse wall) can push its new triangles
// through the other side a few rings away while every triangle keeps its orientation (dragon,
// uniform 8 % with features at 45 degrees: 595 crossing pairs). The guard tests the triangles an
// operation would create exactly (geometry/self_intersections) against every face whose box
// their box touches, found in a hash grid of the current faces (geometry/face_grid) that the
// operations keep up to date.
//
// A crossing that the faces an operation replaces have already (an input that crosses itself,
// whose crossings the split pass multiplies) is not the operation's: refusing every operation next
// to one left the slivers around it (bunny.off: a 6.7-degree triangle at one of its two).
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "geometry/face_grid.h"
#include "mesh/surface_mesh.h"

namespace adasculpt::remesh {

// The places of the vertices before a batch of moves (CrossingGuard::undo_crossing_moves): an
// array per vertex slot, or (a region's relaxation) the current places but for the moved
// vertices, whose places before are kept by their position in a list (`at`: per vertex slot,
// current only where the list agrees; 4 bytes a slot where a copy of every place took 24).
class PlacesBefore {
 public:
  using Vertex = mesh::Vertex;
  explicit PlacesBefore(const std::vector<Point>& per_slot) : per_slot_(per_slot.data()) {}
  PlacesBefore(const Point* current, const std::vector<std::uint32_t>& at, const std::vector<Vertex>& listed,
               const std::vector<Point>& listed_before)
      : current_(current), at_(at.data()), listed_(listed.data()), listed_before_(listed_before.data()),
        n_listed_(listed.size()) {}
  const Point& operator[](std::uint32_t v) const {
    if (per_slot_) return per_slot_[v];
    const std::uint32_t i = at_[v];
    return i < n_listed_ && listed_[i].idx == v ? listed_before_[i] : current_[v];
  }

 private:
  const Point* per_slot_ = nullptr;
  const Point* current_ = nullptr;
  const std::uint32_t* at_ = nullptr;
  const Vertex* listed_ = nullptr;
  const Point* listed_before_ = nullptr;
  size_t n_listed_ = 0;
};

class CrossingGuard {
 public:
  using SurfaceMesh = mesh::SurfaceMesh;
  using Vertex = mesh::Vertex;
  using Halfedge = mesh::Halfedge;
  using Edge = mesh::Edge;
  using Face = mesh::Face;

  // (Re)builds the grid over the mesh's faces; until stop(), the tests below are live and every
  // edit must be reported (fan_changed, flipped). Without it every test passes. The work of one
  // grid is bounded (a fixed number of face pairs per face): once spent, the grid is built again
  // over the current faces, up to kRenewals times per start() or resume(); after that every test fails (the
  // operations are refused) until the next start() or resume(). An unchecked operation was how most of the
  // sweep's new crossings came about: a coarsening pass spent the grid's work within its first
  // iteration (cylinder_locally_refined, turbine, man at uniform lengths).
  void start(const SurfaceMesh& mesh);
  void stop() {
    grid_.clear();
    active_ = false;
  }
  // Between the passes of a batch remesh: the tests pass and edits go unreported, but the grid is
  // kept for resume(), which is only right when nothing edited the mesh in between (a build costs
  // as much as the guard's tests of a whole collapse pass: two per iteration were a sixth of a
  // bunny remesh). A garbage collection in between is allowed: it renumbers the faces only when
  // it drops some, which resume() sees by the face slots and answers with a new grid, as it does
  // when none is kept.
  void suspend(const SurfaceMesh& mesh) {
    active_ = false;
    kept_face_slots_ = mesh.faces_size();
  }
  void resume(const SurfaceMesh& mesh);
  // The same over the listed faces only (region_guard.cpp): a sculpting frame's region and the
  // ring of faces around it, at a cost proportional to them; one grid through the frame's
  // passes. The grid is never renewed: a spent budget refuses the frame's remaining operations.
  void start_region(const SurfaceMesh& mesh, const std::vector<Face>& faces);
  // Sizes the per-slot arrays the region guard uses to the mesh's slots (Remesher::reserve_scratch).
  void reserve_region(const SurfaceMesh& mesh);
  bool active() const { return active_ && grid_.built(); }
  void fan_changed(const SurfaceMesh& mesh, Vertex v) {  // after a move, split or collapse at v
    if (active_) grid_.insert_fan(mesh, v);
  }
  void flipped(const SurfaceMesh& mesh, Edge e);

  // Whether collapsing h (from_vertex into to_vertex, the survivor at `target`; both ends move
  // when both_ends_move) would create a triangle that crosses the surface or is degenerate.
  bool collapse_crosses(const SurfaceMesh& mesh, Halfedge h, const Point& target, bool both_ends_move);
  bool flip_crosses(const SurfaceMesh& mesh, Edge e);
  // Whether splitting e at p would. Even at the midpoint: it lies off the edge by rounding, and
  // where a face touches the edge up to rounding (two meshed sides of a flat part of the input
  // folded onto each other) the halves can cross it.
  bool split_crosses(const SurfaceMesh& mesh, Edge e, const Point& p);
  // The test collapse_crosses passes over the pairs that share w with: whether w's fan as that
  // collapse would leave it is surely embedded (geometry/embedded_fan.h). For the tests.
  bool fan_embedded_after_collapse(const SurfaceMesh& mesh, Halfedge h, const Point& target, bool both_ends_move,
                                   Vertex w);
  // After v moved: whether a face of its fan crosses the surface.
  bool fan_crosses(const SurfaceMesh& mesh, Vertex v) { return fan_crossing(mesh, v).found; }
  // While active: appends the faces whose box (as last reported) touches [lo, hi], some of them
  // deleted or moved since (callers test the current geometry); false when `budget` (cells and
  // entries looked at) ran out first. The coverage check's nearest-face search (coverage.cpp).
  bool gather_faces(const Point& lo, const Point& hi, std::vector<Face>& out, size_t& budget) {
    return active() && grid_.gather(lo, hi, out, budget);
  }

  // A crossing that the faces an operation replaces have already is excused (see above). With
  // `on`, only where those faces met the face crossed: the input's clean-up (Remesher::iterate)
  // otherwise tilted faces of cgal/mpi.off's nearly coplanar overlapping walls into their
  // neighbours beyond the input's own crossings, and the splits after it turned that into 66 new
  // pairs (uniform 0.5 %). Everywhere, it cost the triangles next to an input's crossings their
  // shape (man.off at eps 0.5 %: min angle 21.8 -> 7.4 degrees). Off after start().
  void contain_inherited_crossings(bool on) { contain_inherited_ = on; }

  // After moving many vertices at once (the relaxation and projection): the moved corners of
  // both faces of every new crossing pair (one that did not cross at `before`) with a moved face
  // go back to before[v] (per vertex slot; unmoved vertices equal it), until there is none. Every vertex goes
  // back at most once, and if the mesh at `before` had no crossing the result has none (but for
  // crossings between faces that did not move, which the moves did not make). Rebuilds the
  // grid and leaves the guard active. Returns the vertices sent back.
  size_t undo_crossing_moves(SurfaceMesh& mesh, const std::vector<Point>& before);
  // The same for a region (region_guard.cpp), after start_region over `faces` and the passes that
  // followed it (the same list: the faces they deleted leave it here). `before` must hold the
  // place of every corner of the listed faces.
  size_t undo_region_crossing_moves(SurfaceMesh& mesh, const PlacesBefore& before, std::vector<Face>& faces);

 private:
  struct Candidate {  // a triangle an operation would create, or a face that moved
    Point p[3];
    std::array<std::uint32_t, 3> ids;  // vertex ids: shared ids are shared corners
    Face face;                         // the face itself when it exists (not tested against itself)
  };
  struct Crossing {
    bool found = false;
    size_t triangle = 0;  // which candidate
    Face face;            // the face it crosses (invalid for a degenerate candidate)
  };
  // The first crossing of one of the candidates with a face near them, leaving out the faces
  // with a corner `replaced` (rewritten by the operation) and skip0, skip1.
  // With `before` (positions per vertex slot), a pair that crossed there too is passed over.
  Crossing first_crossing(const SurfaceMesh& mesh, const Candidate* ts, size_t n, Vertex replaced0, Vertex replaced1,
                          Face skip0, Face skip1, const PlacesBefore* before = nullptr);
  // The triangles collapsing h would create, into candidates_ (survivor: h's to_vertex, at target).
  void collapse_candidates(const SurfaceMesh& mesh, Halfedge h, const Point& target, bool both_ends_move);
  // Whether a new triangle (box t_lo, t_hi) that crosses g (corners q) keeps a crossing of g that
  // the faces the operation replaces had already: some of them cross g (and with
  // contain_inherited_, t's box meets g's only where theirs did).
  bool crossed_already(const SurfaceMesh& mesh, Face g, const Point q[3], const std::array<std::uint32_t, 3>& ids,
                       const Point& t_lo, const Point& t_hi, Vertex replaced0, Vertex replaced1, Face skip0,
                       Face skip1) const;
  Crossing fan_crossing(const SurfaceMesh& mesh, Vertex v, const PlacesBefore* before = nullptr);  // fills candidates_
  // Whether w's fan as the operation first_crossing checks would leave it (w's faces but those it
  // replaces, with the new candidates) surely crosses nowhere (geometry/embedded_fan.h). Where a
  // collapse's survivor stays, its current place must be the target (as collapse_crosses asks).
  bool fan_embedded_after(const SurfaceMesh& mesh, std::uint32_t w, const Candidate* ts, size_t n, Vertex replaced0,
                          Vertex replaced1, Face skip0, Face skip1) const;
  // fan_embedded_after, remembered per operation in fans_after_ (cleared by first_crossing).
  bool remembered_fan_embedded_after(const SurfaceMesh& mesh, std::uint32_t w, const Candidate* ts, size_t n,
                                     Vertex replaced0, Vertex replaced1, Face skip0, Face skip1);
  // Whether a candidate with corners a and a face with corners b share a corner whose fan after the
  // operation is embedded: then they do not cross.
  bool shared_fan_embedded(const SurfaceMesh& mesh, const std::array<std::uint32_t, 3>& a,
                           const std::array<std::uint32_t, 3>& b, const Candidate* ts, size_t n, Vertex replaced0,
                           Vertex replaced1, Face skip0, Face skip1);
  // Whether faces with corners a and b share a corner whose fan surely crosses nowhere (undo_crossing_moves).
  bool share_an_embedded_fan(const SurfaceMesh& mesh, const std::array<std::uint32_t, 3>& a,
                             const std::array<std::uint32_t, 3>& b);

  // Builds the grid (cells as long as a few mean edges) with a fresh work budget.
  void build_grid(const SurfaceMesh& mesh);

  geometry::FaceGrid grid_;
  bool active_ = false;
  size_t kept_face_slots_ = 0;  // suspend()
  // Scratch, reused: no allocation once warmed up.
  std::vector<Candidate> candidates_;
  struct Shape {  // first_crossing: a candidate's box and normal (cross(p1 - p0, p2 - p0))
    Point lo, hi;
    Vec3 normal;
  };
  std::vector<Shape> shapes_;
  std::vector<std::pair<std::uint32_t, bool>> fans_after_;  // first_crossing: shared_fan_embedded's answers
  std::vector<Face> near_;
  // undo_crossing_moves: per face slot (a region's: per position in its list)
  std::vector<std::uint8_t> moved_face_;
  std::vector<std::array<std::uint32_t, 3>> face_corners_;
  std::vector<Vec3> face_normals_;
  std::vector<std::uint8_t> face_degenerate_;
  enum : std::uint8_t { kUnknown, kEmbedded, kNotShown };
  std::vector<std::uint8_t> fan_embedded_;  // undo_crossing_moves: per vertex slot, at the current positions
  size_t work_left_ = 0;  // pairs of faces the current grid may still look at (start())
  // Renewals of the grid and its work (renew_budget) a start() allows: the work of a pass stays
  // within a fixed multiple of the mesh's size.
  static constexpr int kRenewals = 4;
  int renewals_left_ = 0;
  bool spent_ = false;              // the renewals too: every test fails until the next start() or resume()
  bool contain_inherited_ = false;  // contain_inherited_crossings
  void reset_budget();              // start() and resume(): renewals, spent_, contain_inherited_
  bool renew_budget(const SurfaceMesh& mesh);  // build_grid, or (none left) spent_
  std::vector<Vertex> to_check_, to_undo_, crossed_fans_;
  // undo_crossing_moves' rounds: the vertices in to_undo_ go back, then the corners of the pairs
  // their fans now make, until none is left (or, with stop_when_spent, until the budget is
  // spent: a spent grid finds a crossing everywhere). A fan that crossed is checked again in the
  // next round (crossed_fans_): a round resolves its first crossing only. Returns the vertices
  // sent back.
  size_t send_back(SurfaceMesh& mesh, const PlacesBefore& before, bool stop_when_spent = false);
  void list_moved_corners(const SurfaceMesh& mesh, const PlacesBefore& before,
                          const std::array<std::uint32_t, 3>& c);  // into to_undo_
  // f's corners, normal, degeneracy and whether it moved, into the sweep's arrays at `key` (its
  // slot, or its position in a region's list); returns whether it moved.
  bool note_face(const SurfaceMesh& mesh, const PlacesBefore& before, Face f, size_t key);
  // The sweep's test of a pair (corners, normals): when the faces cross now but not at `before`,
  // their moved corners go into to_undo_.
  void list_if_crossing_anew(const SurfaceMesh& mesh, const PlacesBefore& before,
                             const std::array<std::uint32_t, 3>& cf, const Vec3& nf,
                             const std::array<std::uint32_t, 3>& cg, const Vec3& ng);
  bool in_region_ = false;            // started by start_region
  bool region_out_of_scale_ = false;  // start_region: the faces span more than the grid's float boxes resolve
  size_t region_faces_ = 0;           // start_region: the list's length
  double grid_cell_ = 0;              // start_region: its cells' size
};

}  // namespace adasculpt::remesh
