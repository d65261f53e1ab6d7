#pragma once
// AngleFigures: the angle figures of the quality report (smallest and largest angle, mean smallest
// angle, shares under 30 and 10 degrees) kept up to date while strokes edit the mesh, for the
// stats a viewer shows after every stroke: quality_report() is a pass over the whole mesh (895 ms
// at 1.1M triangles in the browser), this costs the faces that changed.
//
// Per face slot its smallest and largest angle; sums in fixed point (exact integers, so adding and
// taking back a face never drifts); the extremes per block of slots, so a query scans the blocks,
// not the faces. The owner reports changes as for geometry::FaceSlotTree (mark_vertex, mark_face,
// then sync before reading); slots added or cut off at the end are found by sync itself.
// The extremes equal quality_report's exactly; the mean up to the fixed point's 2^-32 degrees.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/quality.h"
#include "mesh/surface_mesh.h"

namespace adasculpt::geometry {

class AngleFigures {
 public:
  // Recomputed from every face at the next sync(): a new mesh.
  void invalidate() { built_ = false; }
  void mark_vertex(const mesh::SurfaceMesh& m, mesh::Vertex v);  // its faces changed or moved
  void mark_face(mesh::Face f);                                   // this slot changed (or was deleted)
  void sync(const mesh::SurfaceMesh& m);
  // Fills faces, min_angle_deg, max_angle_deg, mean_min_angle_deg, pct_min_angle_lt_30/_lt_10.
  void fill(QualityReport& r) const;
  // Face slots recomputed by the last sync() (tests: the work follows the change, not the mesh).
  size_t last_work() const { return last_work_; }

 private:
  static constexpr std::uint32_t kBlock = 256;
  void resize(size_t slots);
  void set_face(const mesh::SurfaceMesh& m, std::uint32_t slot);  // takes back the old share, adds the new
  void fit_block(std::uint32_t block);

  bool built_ = false;
  std::vector<double> min_deg_, max_deg_;  // per slot; NaN = no live face there
  std::vector<double> block_min_, block_max_;
  std::vector<std::uint8_t> mark_, block_mark_;
  std::vector<std::uint32_t> dirty_, dirty_blocks_;
  size_t synced_faces_ = 0;
  std::int64_t sum_min_fixed_ = 0;  // sum of the live faces' smallest angles, in 2^-32 degrees
  size_t live_ = 0, lt30_ = 0, lt10_ = 0;
  size_t last_work_ = 0;
};

}  // namespace adasculpt::geometry
