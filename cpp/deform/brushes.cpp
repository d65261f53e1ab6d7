#include "deform/brushes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "geometry/normals.h"
#include "geometry/triangle.h"
#include "mesh/flat_walk.h"
#include "mesh/scratch.h"
#include "mesh/vertex_mask.h"

namespace adasculpt::deform {

namespace {
// Displacement per stamp at full strength and falloff, as a fraction of the radius. With the
// default spacing a point is under about 8 stamps as the brush passes over it: a full-strength
// draw stroke raises a ridge of roughly half the radius, like common sculpting tools.
constexpr double kDisplace = 0.1;
// Fraction of the way to the stroke centre a pinch moves a vertex per stamp at full strength.
// Kept well below 1 so that vertices near the centre do not pile up on it in one stamp.
constexpr double kPinch = 0.25;
// Bound on the inflate brush's normal smoothing passes (BrushDeformer::smooth_normals).
constexpr int kMaxNormalPasses = 24;

// BrushTool::Grab is the snake hook; "grab" (its name until the Pull tool's handle grab took the
// word) is still read as a deprecated alias, so older session files replay.
const char* const kNames[] = {"draw", "inflate", "smooth", "flatten", "pinch", "crease", "snakeHook"};
const char* const kFalloffNames[] = {"smooth", "sphere", "sharp", "linear", "constant"};

// Twice the area-weighted normal of the faces around v (not normalised).
Vec3 fan_normal(const SurfaceMesh& mesh, Vertex v) {
  const Point& p = mesh.position(v);
  Vec3 sum(0.0);
  for (mesh::Halfedge h : mesh.halfedges(v)) {
    if (mesh.is_boundary(h)) continue;
    sum += glm::cross(mesh.position(mesh.to_vertex(h)) - p, mesh.position(mesh.to_vertex(mesh.next(h))) - p);
  }
  return sum;
}

// The snake hook's falloff: 1 - 4q^3 + 3q^4 (SculptGL's), flat at the centre. With the
// brushes' (1 - q^2)^3 the vertices under the pointer moved by less than the pointer each stamp
// and the hook fell behind it (85 % of a 3-radii pull on a sphere, 77 % on fandisk; 100 % and
// 104 % with this one; tests/bench/sculptor-compare.mjs).
double grab_falloff(double distance, double radius) {
  if (!(distance < radius)) return 0;
  const double q = distance / radius;
  return 1 - q * q * q * (4 - 3 * q);
}

Vec3 normalized_or_zero(const Vec3& v) {
  const double len = glm::length(v);
  return len > 0 ? v / len : Vec3(0.0);
}
}  // namespace

const char* brush_tool_list() { return "draw, inflate, smooth, flatten, pinch, crease, snakeHook"; }
const char* brush_tool_name(BrushTool tool) { return kNames[static_cast<int>(tool)]; }

std::optional<BrushTool> parse_brush_tool(const std::string& name) {
  for (int i = 0; i < 7; ++i)
    if (name == kNames[i]) return static_cast<BrushTool>(i);
  if (name == "grab") return BrushTool::Grab;  // deprecated alias of "snakeHook"
  return std::nullopt;
}

const char* brush_falloff_list() { return "smooth, sphere, sharp, linear, constant"; }
const char* brush_falloff_name(BrushFalloff falloff) { return kFalloffNames[static_cast<int>(falloff)]; }

std::optional<BrushFalloff> parse_brush_falloff(const std::string& name) {
  for (int i = 0; i < 5; ++i)
    if (name == kFalloffNames[i]) return static_cast<BrushFalloff>(i);
  return std::nullopt;
}

void check_brush_settings(const BrushSettings& s) {
  if (!(s.radius > 0) || !std::isfinite(s.radius)) throw std::invalid_argument("brush: 'radius' must be a positive number");
  if (!(s.strength >= 0 && s.strength <= 1)) throw std::invalid_argument("brush: 'strength' must be between 0 and 1");
  // Below 0.05 a stroke would cost hundreds of remeshing iterations per radius of travel.
  if (!(s.spacing >= 0.05 && s.spacing <= 4)) throw std::invalid_argument("brush: 'spacing' must be between 0.05 and 4");
  if (s.symmetry_axis < -1 || s.symmetry_axis > 2) throw std::invalid_argument("brush: 'symmetry' must be x, y, z or none");
  if (!(s.detail >= 0) || !std::isfinite(s.detail))
    throw std::invalid_argument("brush: 'detail' must be a non-negative length (0: the session's detail)");
}

double brush_falloff(double distance, double radius, BrushFalloff falloff) {
  if (!(distance < radius)) return 0;
  const double q = distance / radius;
  switch (falloff) {
    case BrushFalloff::Smooth: {
      const double t = 1 - q * q;
      return t * t * t;
    }
    case BrushFalloff::Sphere:
      return std::sqrt(1 - q * q);
    case BrushFalloff::Sharp:
      return (1 - q) * (1 - q);
    case BrushFalloff::Linear:
      return 1 - q;
    case BrushFalloff::Constant:
      return 1;
  }
  return 0;
}

Vertex walk_to_nearest_vertex(const SurfaceMesh& mesh, Vertex start, const Point& target) {
  Vertex v = start;
  Vec3 d = mesh.position(v) - target;
  double best = glm::dot(d, d);
  for (bool moved = true; moved;) {  // ends: the distance strictly decreases
    moved = false;
    for (Vertex w : mesh.vertices(v)) {
      d = mesh.position(w) - target;
      const double d2 = glm::dot(d, d);
      if (d2 < best) {
        best = d2;
        v = w;
        moved = true;
      }
    }
  }
  return v;
}

Point closest_point_around(const SurfaceMesh& mesh, Vertex v, const Point& p) {
  Point best = mesh.position(v);
  Vec3 d = best - p;
  double best_d2 = glm::dot(d, d);
  for (mesh::Face f : mesh.faces(v)) {
    Vertex c[3];
    mesh.face_vertices(f, c);
    double bary[3];
    const Point q = geometry::closest_point_on_triangle(p, mesh.position(c[0]), mesh.position(c[1]), mesh.position(c[2]), bary);
    d = q - p;
    if (glm::dot(d, d) < best_d2) {
      best_d2 = glm::dot(d, d);
      best = q;
    }
  }
  return best;
}

void BrushDeformer::grow(size_t n) {
  if (mark_.size() >= n) return;
  mesh::resize_scratch(mark_, n, 0);
  mesh::resize_scratch(in_stamp_, n, 0);
  mesh::resize_scratch(slot_, n, 0);
  mesh::resize_scratch(sum_, n, Vec3(0.0));
  mesh::resize_scratch(count_, n, 0);
}

void BrushDeformer::gather(const SurfaceMesh& mesh, const StampSpec& s, double radius, BrushFalloff falloff) {
  inside_.clear();
  weight_.clear();
  if (++stamp_run_ == 0) {
    std::fill(in_stamp_.begin(), in_stamp_.end(), 0);
    stamp_run_ = 1;
  }
  if (!s.seed.is_valid() || mesh.is_deleted(s.seed)) return;
  const double r2 = radius * radius;
  auto inside = [&](Vertex v) {
    const Vec3 d = mesh.position(v) - s.center;
    return glm::dot(d, d) < r2;
  };
  if (!inside(s.seed)) return;
  in_stamp_[s.seed.idx] = stamp_run_;
  inside_.push_back(s.seed);
  const auto* hc = mesh.halfedge_connectivity_data();
  const mesh::Halfedge* vh = mesh.vertex_halfedge_data();
  std::uint32_t* in_stamp = in_stamp_.data();
  for (size_t i = 0; i < inside_.size(); ++i)  // breadth-first: inside_ is the queue
    mesh::for_each_outgoing(hc, vh, inside_[i], [&](mesh::Halfedge h) {
      const Vertex w = hc[h.idx].to;
      if (in_stamp[w.idx] != stamp_run_) {
        in_stamp[w.idx] = stamp_run_;
        if (inside(w)) inside_.push_back(w);
      }
    });
  for (Vertex v : inside_) weight_.push_back(brush_falloff(glm::length(mesh.position(v) - s.center), radius, falloff));
}

void BrushDeformer::smooth_normals(const SurfaceMesh& mesh, double displacement) {
  // Each vertex moving along its own normal by many edge lengths turns every small wrinkle into a
  // fold (neighbours with different normals move apart), the adaptive sizing refines the folds and
  // the next stamp crumples them further: large inflate strokes grew a mesh from 37k to 3M
  // vertices. Moving along a normal field smoothed over about the displacement keeps neighbours
  // moving together. Jacobi averaging over one ring per pass diffuses over about sqrt(passes)
  // rings, so (displacement / mean edge length)^2 passes, bounded.
  const size_t n = inside_.size();
  mesh::resize_scratch(smooth_normal_, n);
  mesh::resize_scratch(next_normal_, n);
  double edge_sum = 0;
  size_t edges = 0;
  for (size_t k = 0; k < n; ++k) {
    slot_[inside_[k].idx] = std::uint32_t(k);
    smooth_normal_[k] = geometry::vertex_normal(mesh, inside_[k]);
    for (Vertex u : mesh.vertices(inside_[k])) {
      edge_sum += glm::length(mesh.position(u) - mesh.position(inside_[k]));
      ++edges;
    }
  }
  const double mean_edge = edges > 0 ? edge_sum / double(edges) : 0;
  const double ratio = mean_edge > 0 ? displacement / mean_edge : 0;
  const int passes = int(std::min(double(kMaxNormalPasses), std::ceil(ratio * ratio)));
  for (int pass = 0; pass < passes; ++pass) {
    for (size_t k = 0; k < n; ++k) {
      Vec3 sum = smooth_normal_[k];
      for (Vertex u : mesh.vertices(inside_[k]))
        if (in_stamp_[u.idx] == stamp_run_ && slot_[u.idx] < n && inside_[slot_[u.idx]] == u)
          sum += smooth_normal_[slot_[u.idx]];
      next_normal_[k] = normalized_or_zero(sum);
    }
    smooth_normal_.swap(next_normal_);
  }
}

void BrushDeformer::displace(const SurfaceMesh& mesh, const BrushSettings& st, const StampSpec& s) {
  gather(mesh, s, st.radius, st.falloff);
  if (inside_.empty()) return;
  const double sign = st.invert ? -1.0 : 1.0;
  const double amount = st.strength * s.pressure;

  // Region plane: normal and centre weighted by area and falloff (draw, flatten, pinch, crease;
  // smooth, inflate and grab do not use it, and it is a third of a smooth stamp's deformation).
  Vec3 normal(0.0);
  Point centre(0.0);
  if (st.tool != BrushTool::Smooth && st.tool != BrushTool::Inflate && st.tool != BrushTool::Grab) {
    double wsum = 0;
    for (size_t k = 0; k < inside_.size(); ++k) {
      normal += weight_[k] * fan_normal(mesh, inside_[k]);
      centre += weight_[k] * mesh.position(inside_[k]);
      wsum += weight_[k];
    }
    normal = normalized_or_zero(normal);
    centre = wsum > 0 ? centre / wsum : s.center;
  }
  if (st.tool == BrushTool::Inflate) smooth_normals(mesh, kDisplace * st.radius * amount);

  const auto* hc = mesh.halfedge_connectivity_data();  // the smooth brush's Laplacian walks the fans
  const mesh::Halfedge* vh = mesh.vertex_halfedge_data();
  const Point* pos = mesh.positions().data();

  for (size_t k = 0; k < inside_.size(); ++k) {
    const Vertex v = inside_[k];
    const Point& p = mesh.position(v);
    const double w = weight_[k] * amount;
    Vec3 d(0.0);
    switch (st.tool) {
      case BrushTool::Draw:
        d = (sign * kDisplace * st.radius * w) * normal;
        break;
      case BrushTool::Inflate:
        d = (sign * kDisplace * st.radius * w) * smooth_normal_[k];
        break;
      case BrushTool::Smooth: {
        if (mesh.is_boundary(v)) break;  // a Laplacian step would shrink the border
        Point c(0.0);
        int n = 0;
        mesh::for_each_outgoing(hc, vh, v, [&](mesh::Halfedge h) {
          c += pos[hc[h.idx].to.idx];
          ++n;
        });
        if (n > 0) d = w * (c / double(n) - p);
        break;
      }
      case BrushTool::Flatten:
        d = (-sign * w * glm::dot(p - centre, normal)) * normal;
        break;
      case BrushTool::Pinch:
      case BrushTool::Crease: {
        Vec3 t = s.center - p;
        t -= glm::dot(t, normal) * normal;  // in the tangent plane only: pinching must not dig
        if (st.tool == BrushTool::Pinch) {
          d = (sign * kPinch * w) * t;
        } else {
          // Inverted, a crease is a pinched ridge: the pinch stays, the draw goes outward.
          d = (kPinch * w) * t - (sign * 0.5 * kDisplace * st.radius * w) * normal;
        }
        break;
      }
      case BrushTool::Grab:
        d = grab_falloff(glm::length(p - s.center), st.radius) * s.grab_delta;
        break;
    }
    add(v, d);
  }
}

void BrushDeformer::add(Vertex v, const Vec3& d) {
  if (mark_[v.idx] != run_) {
    mark_[v.idx] = run_;
    sum_[v.idx] = Vec3(0.0);
    count_[v.idx] = 0;
    touched_.push_back(v);
  }
  sum_[v.idx] += d;
  count_[v.idx] = std::uint8_t(std::min(255, count_[v.idx] + 1));
}

std::vector<Vertex>& BrushDeformer::apply(SurfaceMesh& mesh, const BrushSettings& settings, const StampSpec* stamps,
                                          int n, const std::vector<Vertex>* mirror) {
  grow(mesh.vertices_size());
  if (++run_ == 0) {
    std::fill(mark_.begin(), mark_.end(), 0);
    run_ = 1;
  }
  touched_.clear();
  if (mirror && n == 2 && settings.symmetry_axis >= 0) {
    // The first stamp's displacements, and each one mirrored onto the vertex's image. A vertex
    // under both stamps gets d + image(d') and its image d' + image(d): the same two terms, so
    // the sums are exact mirror images (a vertex on the plane gets an exactly zero normal part).
    displace(mesh, settings, stamps[0]);
    // Read every first-stamp displacement before adding any image (a vertex and its image may
    // both be under the first stamp).
    const size_t first = touched_.size();
    image_displacement_.resize(first);
    for (size_t k = 0; k < first; ++k) {
      image_displacement_[k] = sum_[touched_[k].idx];
      image_displacement_[k][settings.symmetry_axis] = -image_displacement_[k][settings.symmetry_axis];
    }
    // add() appends to touched_; the first `first` entries stay where they are.
    for (size_t k = 0; k < first; ++k) add((*mirror)[touched_[k].idx], image_displacement_[k]);
  } else {
    for (int i = 0; i < n; ++i) displace(mesh, settings, stamps[i]);
  }
  // The mask scales each vertex's share; a fully masked vertex is not written at all (bit for
  // bit where it was). Its neighbours still join the remeshing region below: the remesher keeps
  // masked vertices out of its scope itself.
  const mesh::VertexProperty<float> mask = mesh::find_mask(mesh);
  Point* pos = mesh.positions().data();
  for (Vertex v : touched_)
    if (!mesh::fully_masked(mask, v)) pos[v.idx] += mesh::unmasked_fraction(mask, v) * (sum_[v.idx] / double(count_[v.idx]));
  moved_ = touched_.size();
  region_ = touched_;
  const auto* hc = mesh.halfedge_connectivity_data();
  const mesh::Halfedge* vh = mesh.vertex_halfedge_data();
  std::uint32_t* mark = mark_.data();
  for (Vertex v : touched_)
    mesh::for_each_outgoing(hc, vh, v, [&](mesh::Halfedge h) {
      const Vertex w = hc[h.idx].to;
      if (mark[w.idx] != run_) {
        mark[w.idx] = run_;
        region_.push_back(w);
      }
    });
  return region_;
}

}  // namespace adasculpt::deform
