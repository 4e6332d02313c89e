#pragma once
// Vector maths types of the kernel: GLM doubles.
#include <glm/glm.hpp>

namespace steady {
using Vec3 = glm::dvec3;
using Mat3 = glm::dmat3;
using Vec2 = glm::dvec2;
}  // namespace steady
