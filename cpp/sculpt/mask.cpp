#include "sculpt/mask.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "deform/brushes.h"
#include "mesh/flat_walk.h"
#include "mesh/scratch.h"
#include "mesh/vertex_mask.h"

namespace adasculpt::sculpt {

namespace {
const char* const kNames[] = {"paint", "erase", "clear", "fill", "invert", "blur", "sharpen"};
constexpr int kKinds = 7;
}  // namespace

const char* mask_op_list() { return "paint, erase, clear, fill, invert, blur, sharpen"; }
const char* mask_op_name(MaskOpKind kind) { return kNames[static_cast<int>(kind)]; }

std::optional<MaskOpKind> parse_mask_op_kind(const std::string& name) {
  for (int i = 0; i < kKinds; ++i)
    if (name == kNames[i]) return static_cast<MaskOpKind>(i);
  return std::nullopt;
}

bool mask_op_has_path(MaskOpKind kind) { return kind == MaskOpKind::Paint || kind == MaskOpKind::Erase; }

void check_mask_op(const MaskOp& op, bool stroke) {
  if (stroke && !mask_op_has_path(op.kind)) throw std::invalid_argument("mask: a stroke's 'op' must be paint or erase");
  if (!mask_op_has_path(op.kind)) return;
  if (op.path.empty() && !stroke) throw std::invalid_argument("mask: 'path' must hold at least one point");
  for (const Point& p : op.path)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw std::invalid_argument("mask: 'path' must hold finite points");
  if (!(op.radius > 0) || !std::isfinite(op.radius)) throw std::invalid_argument("mask: 'radius' must be a positive number");
  if (!(op.strength >= 0 && op.strength <= 1)) throw std::invalid_argument("mask: 'strength' must be between 0 and 1");
}

double mask_falloff(double distance, double radius) {
  if (!(distance < radius)) return 0;
  const double q = distance / radius;
  if (q <= 0.5) return 1;
  const double t = 2 * (1 - q);  // 1 at half the radius, 0 at the rim
  return t * t * (3 - 2 * t);
}

void MaskPainter::begin_run(mesh::SurfaceMesh& mesh, std::vector<mesh::Vertex>& changed) {
  mesh::VertexProperty<float> mask = mesh::find_mask(mesh);
  if (!mask.is_valid()) throw std::logic_error("MaskPainter: the mesh has no mask");
  mask_ = mask.vector().data();
  changed_ = &changed;
  mesh::resize_scratch(changed_mark_, mesh.vertices_size(), 0u);
  mesh::resize_scratch(seen_, mesh.vertices_size(), 0u);
  if (++run_ == 0) {
    std::fill(changed_mark_.begin(), changed_mark_.end(), 0u);
    run_ = 1;
  }
}

void MaskPainter::set(mesh::Vertex v, float value) {
  if (mask_[v.idx] == value) return;
  mask_[v.idx] = value;
  if (changed_mark_[v.idx] != run_) {
    changed_mark_[v.idx] = run_;
    changed_->push_back(v);
  }
}

void MaskPainter::begin_path(const MaskOp& op) {
  op_ = op;
  op_.path.clear();
  started_ = false;
  travelled_ = 0;
}

void MaskPainter::add_point(mesh::SurfaceMesh& mesh, const Point& p, const Locate& locate,
                            std::vector<mesh::Vertex>& changed) {
  begin_run(mesh, changed);
  if (!started_) {
    started_ = true;
    last_point_ = p;
    seed_ = locate(p);
    stamp(mesh, p, seed_);
    return;
  }
  const double spacing = kMaskSpacing * op_.radius;
  const Point a = last_point_;
  const double length = glm::length(p - a);
  double along = spacing - travelled_;  // from a to the next stamp
  while (along <= length) {
    const Point centre = a + (along / length) * (p - a);
    if (seed_.is_valid()) seed_ = deform::walk_to_nearest_vertex(mesh, seed_, centre);
    // A walk can stop at a nearer vertex of another fold; the surface tree knows better.
    if (!seed_.is_valid() || glm::length(mesh.position(seed_) - centre) >= op_.radius) seed_ = locate(centre);
    stamp(mesh, centre, seed_);
    along += spacing;
  }
  travelled_ = length - (along - spacing);
  last_point_ = p;
}

// The vertices inside the stamp's sphere that are connected to the seed through it (as a brush
// stamp finds them: the far side of a thin part is left alone).
void MaskPainter::stamp(const mesh::SurfaceMesh& mesh, const Point& centre, mesh::Vertex seed) {
  if (!seed.is_valid() || mesh.is_deleted(seed)) return;
  if (++stamp_run_ == 0) {
    std::fill(seen_.begin(), seen_.end(), 0u);
    stamp_run_ = 1;
  }
  const double r2 = op_.radius * op_.radius;
  auto inside = [&](mesh::Vertex v) {
    const Vec3 d = mesh.position(v) - centre;
    return glm::dot(d, d) < r2;
  };
  if (!inside(seed)) return;
  queue_.assign(1, seed);
  seen_[seed.idx] = stamp_run_;
  const auto* hc = mesh.halfedge_connectivity_data();
  const mesh::Halfedge* vh = mesh.vertex_halfedge_data();
  for (size_t i = 0; i < queue_.size(); ++i)
    mesh::for_each_outgoing(hc, vh, queue_[i], [&](mesh::Halfedge h) {
      const mesh::Vertex w = hc[h.idx].to;
      if (seen_[w.idx] != stamp_run_) {
        seen_[w.idx] = stamp_run_;
        if (inside(w)) queue_.push_back(w);
      }
    });
  for (mesh::Vertex v : queue_) {
    const float amount = float(op_.strength * mask_falloff(glm::length(mesh.position(v) - centre), op_.radius));
    const float old = mask_[v.idx];
    set(v, op_.kind == MaskOpKind::Paint ? std::max(old, amount) : std::min(old, 1.0f - amount));
  }
}

void MaskPainter::apply_whole(mesh::SurfaceMesh& mesh, MaskOpKind kind, std::vector<mesh::Vertex>& changed) {
  begin_run(mesh, changed);
  if (kind == MaskOpKind::Blur) {
    // Every new value from the old ones: computed first, written after.
    next_.assign(mesh.vertices_size(), 0.0f);
    const auto* hc = mesh.halfedge_connectivity_data();
    const mesh::Halfedge* vh = mesh.vertex_halfedge_data();
    for (mesh::Vertex v : mesh.vertices()) {
      double sum = mask_[v.idx];
      int n = 1;
      mesh::for_each_outgoing(hc, vh, v, [&](mesh::Halfedge h) {
        sum += mask_[hc[h.idx].to.idx];
        ++n;
      });
      next_[v.idx] = std::clamp(float(sum / n), 0.0f, 1.0f);
    }
    for (mesh::Vertex v : mesh.vertices()) set(v, next_[v.idx]);
    return;
  }
  for (mesh::Vertex v : mesh.vertices()) {
    const float m = mask_[v.idx];
    switch (kind) {
      case MaskOpKind::Clear: set(v, 0.0f); break;
      case MaskOpKind::Fill: set(v, 1.0f); break;
      case MaskOpKind::Invert: set(v, 1.0f - m); break;
      case MaskOpKind::Sharpen: set(v, std::clamp(m * m * (3.0f - 2.0f * m), 0.0f, 1.0f)); break;
      default: break;  // paint, erase: add_point()
    }
  }
}

}  // namespace adasculpt::sculpt
