#pragma once
// The scalar and vector types of the core. Positions are double precision so that a mesh
// survives load -> edit -> export without losing digits; rendering converts to float once.
#include <glm/vec3.hpp>

namespace adasculpt {
using Scalar = double;
using Point = glm::dvec3;
using Vec3 = glm::dvec3;
}  // namespace adasculpt
