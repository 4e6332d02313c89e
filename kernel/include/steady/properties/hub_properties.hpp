#pragma once
// Exact integral properties of a hub: its node ball plus its stumps (half-beams cut by the mid-planes).
//
// A stump is convex and contains the node center C, so the hub is star-shaped from C and every property is
// an integral over directions u of powers of the hub's radial function rho(u) = max(R, rho_i(u)):
//     volume = int rho^3/3 dOmega,  first moment = int rho^4/4 u dOmega,  second = int rho^5/5 u u^T dOmega.
// The part a stump adds outside the ball lies over its *cap*: the directions through the circle where its
// cone leaves the node sphere. Stumps add disjoint parts exactly when their caps are disjoint, and then a
// stump's part is a frustum (exit circle to cut disk) minus a spherical cap, in closed form. Where caps
// overlap, the stump's part is integrated over the directions where it is the outermost surface: along
// each meridian of its cap (a half-plane through its axis) the stump's boundary is two straight segments
// (cone generator, cut-disk radius), the stretches hidden inside other stumps are found exactly from
// quadratic equations, and the integrals along the segment are polynomials; only the integral over the
// meridian angle is numerical (adaptive Gauss-Kronrod, tolerance 1e-12 relative by default).
//
// Both beam models are covered: hull model (beam radius = node radius, the cone is tangent to the sphere)
// and explicit radii (smaller, the cone crosses the sphere transversally).
#include <vector>

#include "steady/lattice/hub.hpp"
#include "steady/properties/mass_moments.hpp"

namespace steady {

// A node ball may touch its beam's mid-plane (two balls in contact); beyond rounding (this fraction of the
// half length) it may not cross it: the hub would overlap its neighbour's and the lattice is not clean.
constexpr double kMidPlaneSlack = 1e-12;

// A beam seen from one of its nodes.
struct HubStump {
  Vec3 axis{0.0, 0.0, 1.0};  // unit, from the node toward the other node
  double length = 0.0;       // distance between the two node centers
  double radius = 0.0;       // the beam's end radius at this node
  double other_radius = 0.0; // the beam's end radius at the other node
  // Axial position of the cut disk from the node center; 0: the mid-plane. It may lie inside the node ball as long
  // as its rim lies outside (a crowded hub's collar): the hub then ends at the disk, without the ball's cap beyond
  // it, which belongs to the beam's other half.
  double cut = 0.0;
  double cut_position() const { return cut > 0.0 ? cut : 0.5 * length; }
};

struct HubShape {
  Vec3 center{0.0};
  double radius = 0.0;  // node ball
  std::vector<HubStump> stumps;
};

HubShape hub_shape(const Hub& hub);

// Where the stump's cone leaves the node sphere, and the cap it covers there.
struct StumpCap {
  double exit_position = 0.0;  // along the axis from the node center
  double half_angle = 0.0;     // of the cap, seen from the node center
};
StumpCap stump_cap(double node_radius, const HubStump& stump);

// What one stump adds to its hub outside the node ball.
struct StumpContribution {
  MassMoments moments;        // about the node center; area = visible cone face minus the sphere it covers
  double cone_area = 0.0;     // visible part of the cone's lateral face
  double cut_area = 0.0;      // visible part of the cut disk (inside the lattice: not in moments.area)
  double solid_angle = 0.0;   // directions where this stump is the outermost surface
};

// The stump's part outside the ball when no other stump reaches into its cap, in closed form.
StumpContribution stump_contribution_alone(double node_radius, const HubStump& stump);

// Throws InvalidInput naming the stump when the hub is not made of a ball and frustum stumps: the node
// ball holds a beam's whole cut disk (its rim inside the ball), or a beam's far ball reaches into the near part.
// Both happen only in non-clean lattices.
void validate_hub_shape(const HubShape& hub);

struct HubPropertiesOptions {
  // Relative accuracy asked of the quadrature over overlapping caps (the closed form is exact), shared by
  // the caps integrated; each cap is asked for at least 1e-14 (rounding makes finer requests pointless).
  double tolerance = 1e-12;
  // Integrate every cap numerically, even caps no other stump reaches (tests compare it with the closed form).
  bool quadrature_everywhere = false;
};

struct HubProperties {
  MassMoments moments;          // about the node center
  bool closed_form = true;      // false when some caps overlap and the quadrature was used
  double error_estimate = 0.0;  // the quadrature's estimate, relative to the hub's volume
  std::vector<StumpContribution> stumps;  // in the order of HubShape::stumps
};

HubProperties hub_properties(const HubShape& hub, const HubPropertiesOptions& options = {});

// Moments of the ball alone, about its center.
MassMoments ball_moments(double radius);

// True when two stumps of a hub with node radius R reach into each other outside the ball (their caps
// overlap by more than a rounding error).
bool stump_caps_overlap(double node_radius, const HubStump& a, const HubStump& b);

// Whether any two stumps of the hub overlap outside its ball: stump_caps_overlap over all pairs, faster.
bool any_stump_caps_overlap(const HubShape& hub);
// The same for the hub with every radius multiplied by radius_scale (lengths kept).
bool any_stump_caps_overlap(const HubShape& hub, double radius_scale);

// hub_properties minus (ball + each stump alone): zero when no caps overlap (computed without quadrature).
MassMoments hub_overlap_correction(const HubShape& hub, const HubPropertiesOptions& options = {});

}  // namespace steady
