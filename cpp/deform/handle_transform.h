#pragma once
// The affine transform a user applies to a handle: scale, then rotation, then translation, all
// about the handle centre c:  x' = c + translation + rotation * (scale * (x - c)).
// The sculpting frame blends it over the region of interest (see handle_deformer.h).
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "geometry/portable_math.h"
#include "mesh/types.h"

namespace adasculpt::deform {

struct HandleTransform {
  glm::dvec3 translation{0.0};
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};  // w, x, y, z
  double scale = 1.0;
};

// x' for a point x and handle centre c (the full transform, weight 1).
inline Point apply(const HandleTransform& t, const Point& center, const Point& x) {
  return center + t.translation + t.rotation * (t.scale * (x - center));
}

// The transform that takes the state after `from` to the state after `to` when both are totals
// since the grab began (translation delta, scale ratio, rotation R_to * R_from^-1). Applied about
// the centre after `from` (= the grab centre + from.translation).
inline HandleTransform increment(const HandleTransform& from, const HandleTransform& to) {
  HandleTransform d;
  d.translation = to.translation - from.translation;
  d.scale = from.scale != 0 ? to.scale / from.scale : 1.0;
  d.rotation = glm::normalize(to.rotation * glm::inverse(from.rotation));
  if (d.rotation.w < 0) d.rotation = -d.rotation;  // shortest arc for the slerp
  return d;
}

// Rotation by `radians` about a unit axis. Uses the portable trigonometry (as does the slerp
// below) so that native and WebAssembly builds deform identically.
inline glm::dquat angle_axis(double radians, const glm::dvec3& unit_axis) {
  const double half = 0.5 * radians;
  return glm::dquat(portable::cos(half), portable::sin(half) * unit_axis);
}

// The transform blended with weight w in [0,1]: translation and scale linearly, rotation by
// slerp from the identity, about the centre c. The rotation's axis and angle are found once
// per transform, so a vertex costs one sin/cos pair (nothing for a rotation-free transform):
// a frame blends every vertex of the region.
class Blender {
 public:
  explicit Blender(const HandleTransform& t) : t_(t) {
    const glm::dvec3 v(t.rotation.x, t.rotation.y, t.rotation.z);
    const double s = glm::length(v);
    rotates_ = s > 0;
    if (rotates_) {
      axis_ = v / s;
      half_angle_ = portable::atan2(s, t.rotation.w);
    }
  }
  // Without rotation and scale the blend is c + w t + (x - c): affine in w (refine() uses this).
  bool translates_only() const { return !rotates_ && t_.scale == 1.0; }
  Point operator()(double w, const Point& c, const Point& x) const {
    const Vec3 scaled = (1.0 + w * (t_.scale - 1.0)) * (x - c);
    if (!rotates_) return c + w * t_.translation + scaled;
    const double half = w * half_angle_;
    const glm::dquat r(portable::cos(half), portable::sin(half) * axis_);
    return c + w * t_.translation + r * scaled;
  }

 private:
  HandleTransform t_;
  bool rotates_ = false;
  glm::dvec3 axis_{0.0};
  double half_angle_ = 0;
};

inline Point blend(const HandleTransform& t, double w, const Point& c, const Point& x) { return Blender(t)(w, c, x); }

}  // namespace adasculpt::deform
