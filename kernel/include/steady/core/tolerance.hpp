#pragma once
// The numerical tolerance policy of the kernel (see docs/design.md, "Tolerances").
//
// Powers, inverses and compositions never branch on these: they work on the generator of a similarity
// (log-scale, rotation vector, velocity), whose exponential is continuous through s = 1 and angle 0.
// The tolerances only decide how a similarity is *named* (its kind) and whether two generators commute.

namespace steady {

// |ln s| at or below this counts as scale 1. Frames are read from doubles with ~1e-16 relative error;
// 1e-12 leaves four orders of magnitude of headroom and is far below any intended grading (1e-6 per cell).
constexpr double kLogScaleTolerance = 1e-12;

// A rotation angle (radians) at or below this counts as no rotation. atan2 on quaternion parts keeps the
// angle accurate to ~1e-16 absolute, so the same headroom argument as for the scale applies.
constexpr double kAngleTolerance = 1e-12;

// Lengths (model units, millimetres in FreeCAD) at or below this count as zero: the screw distance of a
// pure rotation, the translation of an identity. 1e-12 mm is far below any machinable feature.
constexpr double kLengthTolerance = 1e-12;

// Frames given by a user (origin, x, y, z) must have |x| = |y| = |z|, be pairwise orthogonal and
// right-handed to this relative tolerance; within it they are re-orthonormalised. FreeCAD placements
// carry ~1e-15 error; 1e-9 accepts values typed with 10 significant digits.
constexpr double kFrameTolerance = 1e-9;

// Two generators are treated as commuting (so that composition keeps the winding of the rotation
// angle) when their Lie bracket is below this, relative to their sizes, and the exponential of the
// summed generator reproduces the product to the same relative accuracy.
constexpr double kCommuteTolerance = 1e-12;

}  // namespace steady
