#pragma once
// Groups hubs into distinct shapes up to similarity, so each distinct shape's expensive geometry (its sphere
// layout and the (u, v) curves of its circles) is computed once and shared by all its similar copies.
//
// A hub is seen in a canonical frame: origin at the ball's center, unit radius, and a rotation fixed by its
// first stump (canonical z) and the first stump not parallel to it (canonical xz-plane). Stumps are listed in a
// fixed order (increasing beam index), which similar hubs of a steady lattice share. Two hubs are the same shape
// when their canonical stump directions and exit positions agree to kHubMatchTolerance.
#include <cstdint>
#include <vector>

#include "steady/core/ball.hpp"
#include "steady/lattice/hub.hpp"
#include "brep/sphere_layout.hpp"

namespace steady {

// Canonical values of similar hubs agree to rounding (~1e-14); 1e-10 separates genuinely different hubs while
// adding at most 1e-10 sphere radii to the placement error of shared curves.
constexpr double kHubMatchTolerance = 1e-10;

// A hub as the builder sees it: the ball and the exit circles of its beams (normals pointing out of the ball).
struct HubGeometry {
  Ball ball;
  std::vector<Circle> exits;
  int kind = 0;                // hubs of different kinds are never the same shape
  std::vector<double> extras;  // further similarity-invariant numbers the shape depends on (compared too)
};

// world point = ball.center + ball.radius * rotation * canonical point.
struct HubPlacement {
  Mat3 rotation{1.0};
  int shape = -1;
};

struct HubCatalog {
  std::vector<HubPlacement> placements;          // one per hub
  std::vector<std::vector<SphereCap>> shapes;    // canonical caps of each distinct shape (its kind and extras
                                                 // are those of its representative)
  std::vector<std::int64_t> representatives;     // the hub whose canonical caps define each shape
};

// The canonical frame of one hub and its caps in that frame.
HubPlacement canonical_frame(const HubGeometry& hub);
std::vector<SphereCap> canonical_caps(const HubGeometry& hub, const Mat3& rotation);

HubCatalog catalog_hubs(const std::vector<HubGeometry>& hubs);

}  // namespace steady
