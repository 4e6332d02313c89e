#pragma once
// Checks of a body the kernel accepted (shared by the BREP and STEP fuzz targets): trimming classifies hubs with
// SolidBody's fast distance bound and decides the rest with the exact distance and containment, so
//   * the fast bound must never exceed the exact distance (a hub would be called clear of a wall it crosses),
//   * a point outside the bounding box by more than the tolerance is never contained.
#include <Standard_Failure.hxx>

#include <cmath>
#include <string>

#include "fuzz_common.hpp"
#include "steady/brep/solid_body.hpp"

namespace steady::fuzz {

inline void check_body(const SolidBody& body) {
  budget_refusals_only("accepted body", [&] {
    try {
      const Box& box = body.bounds();
      const Vec3 mid = 0.5 * (box.lo + box.hi), half = 0.5 * (box.hi - box.lo);
      const double size = body.size();
      // The middle, the box's corners pushed out by a fifth of its size, and points on its axes.
      const Vec3 offsets[] = {{0, 0, 0},     {1.2, 1.2, 1.2}, {-1.2, 1.2, -1.2}, {0.5, 0, 0},
                              {0, -0.5, 0}, {0, 0, 0.9},     {-3, 0.1, 0.2}};
      for (const Vec3& o : offsets) {
        const Vec3 p = mid + o * half;
        const double fast = body.distance_lower_bound(p), exact = body.exact_distance(p);
        if (!(fast <= exact + 1e-9 * size))
          finding("the body's distance lower bound " + std::to_string(fast) + " exceeds the exact distance " +
                  std::to_string(exact));
        const bool outside_box = std::abs(o.x) > 1.0 + 1e-6 || std::abs(o.y) > 1.0 + 1e-6 || std::abs(o.z) > 1.0 + 1e-6;
        // Within a tolerance of the boundary OpenCASCADE counts a point as on it (inside); SolidBody refuses
        // tolerances beyond kMaxBodyRelativeTolerance of the size.
        if (outside_box && exact > 2.0 * kMaxBodyRelativeTolerance * size && body.contains(p))
          finding("a point outside the body's bounding box is classified inside");
      }
    } catch (const Standard_Failure& e) {
      finding(std::string("OpenCASCADE exception on an accepted body: ") + e.GetMessageString());
    }
  });
}

}  // namespace steady::fuzz
