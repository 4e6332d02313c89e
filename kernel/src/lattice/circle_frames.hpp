#pragma once
// Parametrizing circles around an axis, shared by the B-rep code (sphere layouts, hub catalog and cores, the
// builder): one reference direction orthogonal to the axis, chosen the same way everywhere so that frames built
// from it agree, and circle parameters wrapped into one turn.
#include <cmath>

#include "steady/core/vec.hpp"

namespace steady {

// A unit vector orthogonal to the unit vector d.
inline Vec3 any_perpendicular(const Vec3& d) {
  const Vec3 a = std::abs(d.x) < 0.6 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  return glm::normalize(glm::cross(d, a));
}

// t wrapped into [start, start + 2 pi).
inline double wrap_into(double t, double start) {
  constexpr double kTurn = 2.0 * M_PI;
  double r = std::fmod(t - start, kTurn);
  if (r < 0.0) r += kTurn;
  return start + r;
}

}  // namespace steady
