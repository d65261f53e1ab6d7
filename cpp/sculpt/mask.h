#pragma once
// Mask operations: what a mask brush stroke or a mask panel button does to the per-vertex mask
// (mesh/vertex_mask.h). Each is one Session::mask() call, one undo step and one session-file step
// {"mask": {"op": ..., ...}} (session_file.h).
//
//   paint / erase  along `path` (surface points), a stamp every kMaskSpacing x radius: a stamp is
//                  solid over the inner half of its radius and fades to nothing at the rim, so a
//                  stroke leaves a fully masked band with a soft edge. paint raises the mask to
//                  strength x falloff (never lowers it), erase lowers it to 1 - strength x falloff:
//                  going over the same place again changes nothing, whatever the pointer's speed.
//   clear / fill   every vertex to 0 / 1.
//   invert         every vertex to 1 - mask.
//   blur           every vertex to the mean of itself and its neighbours (one pass).
//   sharpen        every vertex to smoothstep(mask): values move away from 1/2 towards 0 or 1.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "mesh/surface_mesh.h"

namespace adasculpt::sculpt {

enum class MaskOpKind { Paint, Erase, Clear, Fill, Invert, Blur, Sharpen };

// "paint, erase, clear, fill, invert, blur, sharpen" (for error messages).
const char* mask_op_list();
const char* mask_op_name(MaskOpKind kind);
std::optional<MaskOpKind> parse_mask_op_kind(const std::string& name);
// Paint and erase follow a path; the others change the whole mask.
bool mask_op_has_path(MaskOpKind kind);

struct MaskOp {
  MaskOpKind kind = MaskOpKind::Paint;
  std::vector<Point> path;  // paint / erase: surface points
  double radius = 0;        // paint / erase: absolute length
  double strength = 1;      // paint / erase: 0..1
};
// Throws std::invalid_argument "mask: 'radius' must be a positive number" and the like. A
// stroke (stroke = true: a paint or erase whose points come one by one) has no path yet.
void check_mask_op(const MaskOp& op, bool stroke = false);

// Stamps every this fraction of the radius along a paint / erase path.
constexpr double kMaskSpacing = 0.25;

// 1 over the inner half of the radius, then a smoothstep down to 0 at the radius.
double mask_falloff(double distance, double radius);

// Applies mask operations to a mesh whose mask exists (Session::mask creates it). Every call
// appends the vertices whose value it changed to `changed`, once each.
class MaskPainter {
 public:
  // A live vertex near p (the session answers from its surface tree).
  using Locate = std::function<mesh::Vertex(const Point& p)>;
  // Clear, fill, invert, blur, sharpen.
  void apply_whole(mesh::SurfaceMesh& mesh, MaskOpKind kind, std::vector<mesh::Vertex>& changed);
  // A paint or erase stroke, point by point as the pointer moves (op.path is not read): the first
  // point stamps at once, later ones every kMaskSpacing x radius along the segment from the last.
  void begin_path(const MaskOp& op);
  void add_point(mesh::SurfaceMesh& mesh, const Point& p, const Locate& locate, std::vector<mesh::Vertex>& changed);

 private:
  void stamp(const mesh::SurfaceMesh& mesh, const Point& centre, mesh::Vertex seed);
  void set(mesh::Vertex v, float value);
  void begin_run(mesh::SurfaceMesh& mesh, std::vector<mesh::Vertex>& changed);

  MaskOp op_;  // of the stroke in progress (its path unused)
  bool started_ = false;
  Point last_point_{0.0};
  double travelled_ = 0;  // since the last stamp
  mesh::Vertex seed_;     // near the last stamp: the next one walks from it

  float* mask_ = nullptr;                  // the mesh's mask values, during apply()
  std::vector<mesh::Vertex>* changed_ = nullptr;
  // Per vertex slot: == run_ when listed as changed in this apply(), == stamp_run_ when reached
  // by this stamp's flood (never cleared in full).
  std::vector<std::uint32_t> changed_mark_, seen_;
  std::uint32_t run_ = 0, stamp_run_ = 0;
  std::vector<mesh::Vertex> queue_;
  std::vector<float> next_;  // blur: the new values, written after all are computed
};

}  // namespace adasculpt::sculpt
