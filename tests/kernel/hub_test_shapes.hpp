#pragma once
// Random hubs for the property tests, and a point-membership test that follows the definition of a hub
// (ball, plus each beam's convex hull of two balls cut at the mid-plane) with nothing shared with the kernel.
#include <random>

#include "steady/properties/hub_properties.hpp"
#include "test_support.hpp"

namespace steady::test {

enum class BeamModel { Hull, ExplicitRadii };

// A hub of node radius 1 with `stumps` beams in random directions. Hull model: beam radius 1 at the node,
// the far node's radius in [0.6, 1.4]. Explicit radii: beam radii in [0.25, 0.8] at both ends.
inline HubShape random_hub(std::mt19937_64& rng, int stumps, BeamModel model) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  HubShape h;
  h.center = random_vec(rng, 3.0);
  h.radius = 1.0;
  for (int k = 0; k < stumps; ++k) {
    HubStump s;
    s.axis = random_unit(rng);
    s.length = 2.2 + 3.0 * u(rng);
    if (model == BeamModel::Hull) {
      s.radius = 1.0;
      s.other_radius = 0.6 + 0.8 * u(rng);
    } else {
      s.radius = 0.25 + 0.55 * u(rng);
      s.other_radius = 0.25 + 0.55 * u(rng);
    }
    h.stumps.push_back(s);
  }
  return h;
}

// Is p (relative to the hub center) inside the hub?
inline bool inside_hub(const HubShape& h, const Vec3& p) {
  if (glm::dot(p, p) <= h.radius * h.radius) return true;
  for (const HubStump& s : h.stumps) {
    const double x = glm::dot(p, s.axis);
    if (x > 0.5 * s.length) continue;  // beyond the mid-plane cut
    // the beam: hull of ball (0, r) and ball (L axis, r')
    const Vec3 b = s.length * s.axis;
    if (glm::dot(p, p) <= s.radius * s.radius) return true;
    if (glm::dot(p - b, p - b) <= s.other_radius * s.other_radius) return true;
    const double sin_phi = (s.radius - s.other_radius) / s.length;
    const double cos_phi = std::sqrt(1.0 - sin_phi * sin_phi);
    const double rho = glm::length(p - x * s.axis);
    const bool between_tangent_circles = x >= s.radius * sin_phi && x <= s.length + s.other_radius * sin_phi;
    if (between_tangent_circles && x * sin_phi + rho * cos_phi <= s.radius) return true;
  }
  return false;
}

// Distance from the hub center to its farthest point.
inline double hub_reach(const HubShape& h) {
  double reach = h.radius;
  for (const HubStump& s : h.stumps) {
    const double sin_phi = (s.radius - s.other_radius) / s.length;
    const double cos_phi = std::sqrt(1.0 - sin_phi * sin_phi);
    const double x = 0.5 * s.length;
    reach = std::max(reach, std::hypot(x, (s.radius - x * sin_phi) / cos_phi));
  }
  return reach;
}

}  // namespace steady::test
