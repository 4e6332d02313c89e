#pragma once
// Where a crowded hub's stumps stop meeting: the collars. A hub whose exit circles overlap is built (as a B-rep
// core or a mesh) as the union of its ball and its stumps up to one collar circle per stump; beyond the collars
// the beams run free, like the beams of clean hubs beyond their exit circles. Everything here is in the hub's
// canonical frame (unit ball at the origin) and free of OpenCASCADE.
#include <vector>

#include "steady/core/vec.hpp"
#include "lattice/cone_envelope.hpp"
#include "lattice/hub_catalog.hpp"
#include "steady/lattice/hub.hpp"

namespace steady {

// One stump in the canonical frame of its hub.
struct CoreStump {
  Vec3 direction{0.0, 0.0, 1.0};  // unit, toward the other node
  double sin_phi = 0.0;           // the beam's radius at axial x is (end_radius - x sin_phi) / cos_phi
  double end_radius = 1.0;        // the beam's end ball radius here (1: the hull model, tangent to the ball)
  double exit = 0.0;              // axial position where the beam's cone leaves the sphere
  double radius_at(double x) const;
};

enum class CoreKind { Hull, Transversal };

// Where the collars go: per stump the smallest axial position at which the stump's cross-section circle lies
// outside every other stump and the stumps' angular cones beyond their collars are disjoint (a cone through the
// ball's center narrows as seen from it, so beyond the collars the stumps never meet). Throws InvalidInput
// (field "hub") when no collar up to `max_position` works.
std::vector<double> place_collars(const std::vector<CoreStump>& stumps, CoreKind kind, double max_position);

// Whether every stump has the same end radius rho (0 < rho <= 1): then all cones are tangent to one sphere around
// the ball's center, and the B-rep builds the core from their envelope arrangement without a Boolean.
bool share_end_radius(const std::vector<CoreStump>& stumps);

// That shared end radius rho, for the arrangement. A beam tangent to its ball (the hull model) computes its end
// radius as 1 plus rounding (1 + 2e-16 after a taper or a screw); it is 1, not a ball of radius 1 / rho < 1 that
// the cones would leave at an imaginary exit_v.
double shared_end_radius(const std::vector<CoreStump>& stumps);

// The stumps' cones for the envelope arrangement when they share their end radius rho: scaled by 1 / rho, so
// that they are tangent to the unit sphere and the ball's sphere (radius 1 / rho) meets them at
// exit_v = sqrt(1 / rho^2 - 1) (0 in the hull model).
std::vector<hull::Cone> envelope_cones(const std::vector<CoreStump>& stumps);

// How far beyond its stump's envelope an arranged collar goes. Roomy: twice kCollarClearance, the band of cone
// that trimming's Booleans have always split (docs/brep.md, "hub cores"). Tight: kTightCollarMargin, for beams
// too short for their two hubs' roomy collars (a BCC node whose beams are as thick as the node: the envelope
// reaches 0.990 of the half beam, roomy collars 1.018); the arrangement then checks its envelope against the
// collar with envelope_clearance(Tight).
enum class CollarFit { Roomy, Tight };
constexpr double kTightCollarMargin = 0.005;
double envelope_clearance(CollarFit fit);

// The collars a B-rep core uses. Stumps of one end radius (the hull model, or explicit radii equal at the node): each collar just beyond the envelope where
// the other stumps meet its stump (by the fit's margin), when no stump meets another again farther out; much closer
// to the ball than place_collars, whose collars must also see each other's angular cones apart (needed by the
// mesh's radial graph and the Boolean, not by the arrangement), so thick beams still fit between two hubs.
// Otherwise place_collars (whatever the fit).
std::vector<double> core_collars(const std::vector<CoreStump>& stumps, CoreKind kind, double max_position,
                                 CollarFit fit = CollarFit::Roomy);

// A crowded hub's stumps from its canonical caps and the slopes and end radii in its geometry's extras (see
// hub_geometry), and which kind of core its HubGeometry::kind asks for.
std::vector<CoreStump> core_stumps(const std::vector<SphereCap>& caps, const std::vector<double>& extras);
CoreKind core_kind(int hub_kind);

// A hub's stumps in its canonical frame (unit ball at the origin), from its geometry in the world, and the kind of
// core its beams ask for (Hull when all are tangent to the ball; InvalidInput, field "hub", when tangent and
// thinner beams mix).
std::vector<CoreStump> core_stumps(const Hub& hub);
CoreKind core_kind(const Hub& hub);

// Where a beam's cut goes between two hubs whose stumps run free beyond axial positions `from` and `to` (both
// measured like `cut`, along the beam): the cut stays where it is when it lies well inside the gap (a tenth of it
// from either end) or when there is no gap, else it moves to the gap's middle. The B-rep (cuts between crowded
// cores) and the properties (hubs whose stumps meet beyond the mid-plane) place cuts by this one rule.
double cut_between_collars(double from, double to, double cut);

// Collars are sought up to this many ball radii from the center (beyond, the beam's cut decides).
constexpr double kMaxCollarPosition = 50.0;

// How far the ray from the ball's center along unit w stays in the stump up to its collar (0 when it meets the
// stump only outside the ball). The hub up to its collars is star-shaped from the center: its boundary lies at
// max(1, max over the stumps of stump_reach) along every direction outside the collars' cones.
double stump_reach(const CoreStump& s, double collar, const Vec3& w);

// stump_reach for many directions (a mesh template asks it millions of times): the stump's unit axis and slope
// worked out once, and a direction on the ball's side of the plane where the cone touches its end ball answered
// by one dot product (the full formula gives 0 there too).
class StumpReach {
 public:
  StumpReach(const CoreStump& s, double collar);
  double operator()(const Vec3& w) const {
    const double k = glm::dot(axis_, w);
    if (k < quick_zero_) return 0.0;
    return reach(k);
  }
  // The reach where it may exceed the ball's (1), else 0: the stump's boundary lies beyond the sphere only along
  // directions inside its exit circle (k above the exit circle's cos), so a hub's piece along a direction is
  // found by one dot product for most of its stumps.
  double beyond_ball(const Vec3& w) const {
    const double k = glm::dot(axis_, w);
    return k < exit_k_ ? 0.0 : k < quick_zero_ ? 0.0 : reach(k);
  }
  const Vec3& axis() const { return axis_; }
  double cos_phi() const { return cos_phi_; }
  double exit_k() const { return exit_k_; }

 private:
  double reach(double k) const;
  Vec3 axis_;
  double sin_phi_, cos_phi_, end_radius_, start_, collar_;
  double quick_zero_;  // below this k the reach is 0 (a margin under start, so rounding cannot tell otherwise)
  double exit_k_;      // below this k the reach is at most 1 (a margin under the exit circle's cos)
};

// The hub's volume up to its collars, by integrating the radial distance of its boundary over directions from
// the ball's center (the core is star-shaped from there): an independent check of the cores in the tests.
double core_volume_by_quadrature(const std::vector<CoreStump>& stumps, const std::vector<double>& collars,
                                 int resolution);

}  // namespace steady
