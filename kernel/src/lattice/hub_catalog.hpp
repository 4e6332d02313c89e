#pragma once
// Groups hubs into distinct shapes up to similarity, so each distinct shape's expensive geometry (its sphere
// layout and the (u, v) curves of its circles) is computed once and shared by all its similar copies.
//
// A hub is seen in a canonical frame: origin at the ball's center, unit radius, and a rotation fixed by its
// first stump (canonical z) and the first stump not parallel to it (canonical xz-plane). Stumps are listed in a
// fixed order (increasing beam index), which similar hubs of a steady lattice share. Two hubs are the same shape
// when their canonical stump directions and exit positions agree to kHubMatchTolerance.
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "steady/core/ball.hpp"
#include "steady/core/errors.hpp"
#include "steady/lattice/beam_frustum.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/hub.hpp"

namespace steady {

// A cap of the unit sphere: the points p with dot(p, direction) >= exit (|exit| < 1). Its circle is
//     p(t) = exit * direction + rho (cos t e1 + sin t e2),  rho = sqrt(1 - exit^2),  e2 = direction x e1,
// turning counterclockwise seen from outside the sphere.
struct SphereCap {
  Vec3 direction{0.0, 0.0, 1.0};
  double exit = 0.0;
};


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

// Caps of a hub's exit circles on its sphere pairwise apart (the clean condition on one ball).
inline bool caps_disjoint(const Ball& ball, const std::vector<Circle>& exits) {
  for (std::size_t a = 0; a < exits.size(); ++a)
    for (std::size_t b = a + 1; b < exits.size(); ++b) {
      auto angle = [&](const Circle& c) {
        return std::atan2(c.radius, glm::dot(c.center - ball.center, c.normal));
      };
      const double between = std::atan2(glm::length(glm::cross(exits[a].normal, exits[b].normal)),
                                        glm::dot(exits[a].normal, exits[b].normal));
      if (between - angle(exits[a]) - angle(exits[b]) < kCleanAngularGap) return false;
    }
  return true;
}

// A built ball's hub: its stumps (the beams `built` says are part of it, with the end at this ball), their exit
// circles, and its kind: 0 when the circles keep apart (clean), else a core (1: hull model, 2: transversal), with
// the numbers its core depends on in `extras` (per stump its slope and end radius in ball radii).
template <class Built>
HubGeometry hub_geometry(const FlatLattice& f, const std::vector<BeamFrustum>& frustums, std::int64_t i,
                         const Built& built, std::vector<std::pair<std::int64_t, int>>& stumps) {
  HubGeometry g;
  g.ball = f.balls[i];
  std::vector<double> slopes, end_radii;
  bool all_tangent = true, all_transversal = true;
  for (const std::int64_t* e = f.incident_begin(i); e != f.incident_end(i); ++e) {
    if (!built(*e)) continue;
    const int end = f.beams[*e].a == i ? 0 : 1;
    const BeamFrustum& fr = frustums[*e];
    stumps.emplace_back(*e, end);
    g.exits.push_back(end == 0 ? fr.circle_a : fr.circle_b);
    const double r = end == 0 ? f.beams[*e].ra : f.beams[*e].rb;
    slopes.push_back(end == 0 ? fr.cone.sin_phi : -fr.cone.sin_phi);
    end_radii.push_back(r / g.ball.radius);
    all_tangent = all_tangent && r >= g.ball.radius * (1.0 - 1e-12);
    all_transversal = all_transversal && r < g.ball.radius * (1.0 - 1e-9);
  }
  if (!caps_disjoint(g.ball, g.exits)) {
    if (!all_tangent && !all_transversal)
      fail_input("hub", "ball " + std::to_string(i) +
                            " mixes beams tangent to it (hull model) with thinner beams, and their circles overlap");
    g.kind = all_tangent ? 1 : 2;
    for (std::size_t s = 0; s < slopes.size(); ++s) g.extras.push_back(slopes[s]), g.extras.push_back(end_radii[s]);
  }
  return g;
}


}  // namespace steady
