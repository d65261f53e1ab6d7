#pragma once
// The affine transform a user applies to a handle: scale, then rotation, then translation, all
// about the handle centre c:  x' = c + translation + rotation * (scale * (x - c)).
// The sculpting frame blends it over the region of interest (see handle_deformer.h).
#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

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

}  // namespace adasculpt::deform
