#pragma once
#include "steady/core/vec.hpp"

namespace steady {

// A closed solid ball. Radius 0 is a point (used by point-membership queries).
struct Ball {
  Vec3 center{0.0};
  double radius = 0.0;
};

}  // namespace steady
