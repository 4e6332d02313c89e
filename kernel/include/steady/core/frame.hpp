#pragma once
#include "steady/core/vec.hpp"

namespace steady {

// A frame (origin, x, y, z): a right-handed orthogonal basis with |x| = |y| = |z| = its scale.
// It represents the similarity taking the unit frame (0, e1, e2, e3) to it: p -> origin + p.x x + p.y y + p.z z.
struct Frame {
  Vec3 origin{0.0};
  Vec3 x{1.0, 0.0, 0.0};
  Vec3 y{0.0, 1.0, 0.0};
  Vec3 z{0.0, 0.0, 1.0};
};

// Throws InvalidInput naming `field` when the frame is not a scaled orthonormal right-handed basis
// within kFrameTolerance (relative), or holds a NaN or infinity.
void validate_frame(const Frame& frame, const char* field);

}  // namespace steady
