#pragma once
// Rotation matrices from an axis and an angle (Rodrigues' formula), written once for the kernel.
#include "steady/core/vec.hpp"

namespace steady {

// The rotation about the unit vector `axis` by the angle whose cosine and sine are c and s (right-hand rule).
inline Mat3 axis_rotation(const Vec3& axis, double c, double s) {
  const Vec3& n = axis;
  const double C = 1.0 - c;
  Mat3 r;  // glm is column-major: r[col][row]
  r[0][0] = c + n.x * n.x * C;
  r[1][0] = n.x * n.y * C - n.z * s;
  r[2][0] = n.x * n.z * C + n.y * s;
  r[0][1] = n.y * n.x * C + n.z * s;
  r[1][1] = c + n.y * n.y * C;
  r[2][1] = n.y * n.z * C - n.x * s;
  r[0][2] = n.z * n.x * C - n.y * s;
  r[1][2] = n.z * n.y * C + n.x * s;
  r[2][2] = c + n.z * n.z * C;
  return r;
}

}  // namespace steady
