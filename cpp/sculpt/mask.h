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
// Throws std::invalid_argument "mask: 'radius' must be a positive number" and the like.
void check_mask_op(const MaskOp& op);

// Stamps every this fraction of the radius along a paint / erase path.
constexpr double kMaskSpacing = 0.25;

// 1 over the inner half of the radius, then a smoothstep down to 0 at the radius.
double mask_falloff(double distance, double radius);

class MaskPainter {
 public:
  // A live vertex near p (the session answers from its surface tree).
  using Locate = std::function<mesh::Vertex(const Point& p)>;
  // Applies op to mesh's mask, which must exist (Session::mask creates it). Appends every vertex
  // whose value changed to `changed`, once each.
  void apply(mesh::SurfaceMesh& mesh, const MaskOp& op, const Locate& locate, std::vector<mesh::Vertex>& changed);

 private:
  void stamp(const mesh::SurfaceMesh& mesh, const MaskOp& op, const Point& centre, mesh::Vertex seed);
  void set(mesh::Vertex v, float value);
  void whole(const mesh::SurfaceMesh& mesh, MaskOpKind kind);
  void begin_run(size_t vertex_slots);

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
