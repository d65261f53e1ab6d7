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

// slerp(identity, q, w) for a unit quaternion q: the rotation about q's axis by w times its
// angle. Equal to glm::slerp from the identity, without the platform's sin/acos.
inline glm::dquat slerp_from_identity(const glm::dquat& q, double w) {
  const glm::dvec3 v(q.x, q.y, q.z);
  const double s = glm::length(v);
  if (!(s > 0)) return glm::dquat(1.0, 0.0, 0.0, 0.0);
  const double half = portable::atan2(s, q.w) * w;
  return glm::dquat(portable::cos(half), (portable::sin(half) / s) * v);
}

// The transform blended with weight w in [0,1]: translation and scale linearly, rotation by
// slerp from the identity, about the centre c.
inline Point blend(const HandleTransform& t, double w, const Point& c, const Point& x) {
  const glm::dquat r = slerp_from_identity(t.rotation, w);
  return c + w * t.translation + r * ((1.0 + w * (t.scale - 1.0)) * (x - c));
}

}  // namespace adasculpt::deform
