#pragma once
// Distance between two convex bodies given by their support maps (GJK: Gilbert, Johnson, Keerthi 1988).
// Used by the clean check for beam-beam separation, where no closed form exists. Each step yields a lower and an
// upper bound of the distance; the iteration stops as soon as the bounds decide the question asked.
#include <functional>

#include "steady/lattice/hub.hpp"
#include "steady/core/vec.hpp"

namespace steady {

// A convex body given by its support map: support(d) returns a point of the body maximizing dot(d, point).
using SupportMap = std::function<Vec3(const Vec3& direction)>;

struct DistanceBounds {
  double lower = 0.0;  // the bodies are at least this far apart (0 when they may intersect)
  double upper = 0.0;  // and at most this far
  bool intersecting = false;  // the origin was enclosed: the bodies overlap
};

// Bounds of the distance between bodies A and B. Stops when lower > stop_above, when upper <= stop_below, or
// when upper - lower <= relative_tolerance * upper (converged).
DistanceBounds convex_distance(const SupportMap& a, const SupportMap& b, double stop_above, double stop_below,
                               double relative_tolerance = 1e-12, int max_iterations = 200);

// Support maps of the shapes the lattice is made of.
Vec3 disk_support(const Circle& disk, const Vec3& direction);
// The convex hull of two parallel or non-parallel disks (a frustum when they share an axis).
Vec3 disk_hull_support(const Circle& a, const Circle& b, const Vec3& direction);

}  // namespace steady
