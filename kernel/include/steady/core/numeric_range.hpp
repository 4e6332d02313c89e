#pragma once
// The range of values the kernel supports (docs/design.md, "Numerical range"). Inputs outside it are refused
// when they are made, with a message naming the field, instead of turning into overflowed or meaningless
// geometry later.
#include <string>

#include "steady/core/vec.hpp"

namespace steady {

// Coordinates, translations and lengths in model units (millimetres in FreeCAD): 1e12 mm is a million km.
// Squared distances of such coordinates (1e24) are far from overflow, and a ball of 1e-3 mm still has 3
// significant digits at the far end of the range.
constexpr double kMaxCoordinate = 1e12;

// Rotation angles in radians: 1e6 rad is 160,000 turns, far beyond any winding a design asks for, and
// cos/sin are still evaluated to ~1e-10 there (argument reduction of a double of that size).
constexpr double kMaxAngle = 1e6;

// |ln s| of a scale: exp(690) ~ 1e300, beyond which a radius overflows.
constexpr double kMaxLogScale = 690.0;

// InvalidInput naming `field` unless the value (each component) is finite and within +-limit.
void require_within(double value, double limit, const std::string& field);
void require_within(const Vec3& value, double limit, const std::string& field);

}  // namespace steady
