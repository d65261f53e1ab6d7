// The crossing guard of a sculpting frame's region iterations (issue 17 item 2): the grid holds
// the region's faces and the ring around them, never the whole mesh, so that a frame pays for
// its region only; one grid serves the frame's collapses and flips and then its relaxation (the
// relaxed faces' entries updated in place, as the operations update theirs). Harsh strokes (four
// rounds of pinch, crease and draw on the bunny's ear, tests/cpp/remesh_region_guard_test.cpp)
// create 663 crossing pairs in 100 of 320 region iterations without it, none with it.
//
// Its cost is the region's, every frame: a build of the grid over the list before the collapses,
// the operations' tests, and after the relaxation (which moves most of the region: of 8.7k moved
// vertices, 8.4k by more than 1 % of the mean edge) a second build and a sweep over all pairs of
// touching boxes. The dragon pull (10k-vertex ROI, bash scripts/pull-frames-callgrind.sh):
// 49.6M / 56.1M / 66.9M instructions per frame (median / p95 / max) without it, 79.9M / 123.8M /
// 189.6M with it. Hence off by default (Remesher::set_region_crossing_guard).
//
// Not covered: faces outside the list. A region's operations reach the ring around it only, but
// a sheet of the mesh that is not in the region (a grab pulling the region through another part)
// is not in the grid.
#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "geometry/self_intersections.h"
#include "mesh/scratch.h"
#include "remesh/crossing_guard.h"

namespace adasculpt::remesh {

namespace {
// Cells as long as this many mean edges of the listed faces, as the whole-mesh grid's: one size
// for the operations' queries and the relaxation's sweep over all pairs in a cell.
constexpr double kRegionCellEdges = 2.0;
// The work one region grid allows, per listed face and at least: as the whole-mesh grid's, but a
// frame's floor is lower (a region of a few hundred faces looks at a few thousand pairs).
constexpr size_t kRegionWorkPerFace = 256;
constexpr size_t kRegionMinWork = 100000;

// The regions the grid's boxes (floats: 24 bits) can still tell apart span fewer than this many of
// their shortest edges; see undo_region_crossing_moves.
constexpr double kMaxRegionShortestEdgesAcross = 1 << 24;

// The mean edge of the faces (of a sample: only the cells' size depends on it); in
// *out_of_scale, whether their extent exceeds kMaxRegionShortestEdgesAcross shortest edges.
double mean_edge_of(const mesh::SurfaceMesh& mesh, const std::vector<mesh::Face>& faces, bool* out_of_scale) {
  constexpr size_t kSampleEvery = 8;
  double sum = 0, shortest2 = std::numeric_limits<double>::infinity();
  size_t sampled = 0;
  Point lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (size_t i = 0; i < faces.size(); ++i) {
    mesh::Vertex v[3];
    mesh.face_vertices(faces[i], v);
    const Point &a = mesh.position(v[0]), &b = mesh.position(v[1]), &c = mesh.position(v[2]);
    const double ab2 = glm::dot(a - b, a - b);
    if (ab2 > 0) shortest2 = std::min(shortest2, ab2);
    lo = glm::min(lo, a);
    hi = glm::max(hi, a);
    if (i % kSampleEvery) continue;
    sum += std::sqrt(ab2) + glm::length(b - c) + glm::length(c - a);
    ++sampled;
  }
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 0.0});
  *out_of_scale = extent > kMaxRegionShortestEdgesAcross * std::sqrt(shortest2);
  return sampled == 0 ? 0.0 : sum / (3.0 * static_cast<double>(sampled));
}
}  // namespace

void CrossingGuard::reserve_region(const SurfaceMesh& mesh) {
  grid_.reserve_listed(mesh.faces_size());
  mesh::resize_scratch(fan_embedded_, mesh.vertices_size(), std::uint8_t(kUnknown));
}

void CrossingGuard::start_region(const SurfaceMesh& mesh, const std::vector<Face>& faces) {
  reset_budget();
  renewals_left_ = 0;  // a renewal would build over the whole mesh: refuse instead
  in_region_ = true;
  region_faces_ = faces.size();
  if (faces.empty()) {
    stop();
    return;
  }
  grid_cell_ = kRegionCellEdges * mean_edge_of(mesh, faces, &region_out_of_scale_);
  grid_.build(mesh, grid_cell_, faces);
  work_left_ = kRegionMinWork + kRegionWorkPerFace * faces.size();
  active_ = true;
}

// A grid the region's faces defeat (every face in a few cells) spends its budget: the moves not
// sent back by then stay, as the whole-mesh sweep leaves them, since a spent grid finds crossings
// everywhere. A region out of scale keeps its moves too: a grab about a pivot at 1e30 rounds a
// whole region to a few points (extent 4e29, shortest edges of its rounding, 1e13), the
// relaxation is what untangles it, and sending 660 of its 760 vertices back left it degenerate
// (reliability_messy_input_test: the field's factorisation failed in the next frame). (Not "more
// than half the vertices cross": harsh pinch strokes do that in many calls, and their crossings
// are real.) Its collapses and flips stay checked. A degenerate triangle (no face crossed) is no
// crossing: left to fix_bad_faces, as the sweep leaves it.
size_t CrossingGuard::undo_region_crossing_moves(SurfaceMesh& mesh, const PlacesBefore& before,
                                                 std::vector<Face>& faces) {
  if (!active() || !in_region_ || region_out_of_scale_ || faces.size() != region_faces_) return 0;
  // The faces the passes deleted leave the list; the others' corners, normals and moves by
  // position in it.
  const std::uint8_t* fdel = mesh.face_deleted_data();
  faces.erase(std::remove_if(faces.begin(), faces.end(), [&](Face f) { return fdel[f.idx] != 0; }), faces.end());
  const size_t n = faces.size();
  mesh::resize_scratch(face_corners_, n);
  mesh::resize_scratch(face_normals_, n);
  mesh::resize_scratch(face_degenerate_, n);
  mesh::resize_scratch(moved_face_, n);
  mesh::resize_scratch(fan_embedded_, mesh.vertices_size(), std::uint8_t(kUnknown));  // (the frame's new vertices)
  bool any = false;
  for (size_t i = 0; i < n; ++i) {
    if (!note_face(mesh, before, faces[i], i)) continue;
    any = true;
    for (const std::uint32_t c : face_corners_[i]) fan_embedded_[c] = kUnknown;
  }
  if (!any) return 0;
  // The grid again, at the relaxed places. Updating the moved faces' entries instead (in place
  // where they kept their cells, a query around each of the others: a fifth of them left their
  // cells) cost more than this build: the dragon pull's frames 81.6M / 129.8M / 211.4M
  // instructions (median / p95 / max) against 80.2M / 124.3M / 190.1M.
  grid_.build(mesh, grid_cell_, faces);
  region_faces_ = n;
  work_left_ = kRegionMinWork + kRegionWorkPerFace * n;
  spent_ = false;
  to_undo_.clear();
  auto wanted = [&](std::uint32_t i, std::uint32_t j) {
    return (moved_face_[i] || moved_face_[j]) && !face_degenerate_[i] && !face_degenerate_[j] &&
           !share_an_embedded_fan(mesh, face_corners_[i], face_corners_[j]);
  };
  const bool swept = grid_.for_each_overlapping_listed_pair(work_left_, wanted, [&](std::uint32_t i, std::uint32_t j) {
    list_if_crossing_anew(mesh, before, face_corners_[i], face_normals_[i], face_corners_[j], face_normals_[j]);
    return true;
  });
  if (!swept) return 0;  // spent: see above
  return send_back(mesh, before, true);
}

}  // namespace adasculpt::remesh
