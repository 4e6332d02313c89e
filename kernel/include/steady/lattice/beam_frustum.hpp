#pragma once
// The part of a beam that lies outside its two node balls, bounded by the two circles where the beam's cone
// leaves the node spheres (its "exit circles"). With explicit end radii thinner than the nodes the circles are
// transversal; in the hull model they are the tangent circles. The solid between the two exit planes is the
// frustum; the beam adds to the lattice exactly that frustum minus the two spherical caps beyond the exit
// planes (which lie inside the node balls).
#include <vector>

#include "steady/core/ball.hpp"
#include "steady/lattice/hub.hpp"

namespace steady {

struct BeamFrustum {
  BeamCone cone;                // the convex hull of the two end balls, oriented from node a to node b
  bool exists = false;          // false when one end ball contains the other, or the nodes overlap so much
                                // that the exit planes cross (no part of the beam outside both nodes)
  double exit_a = 0.0;          // axial position of the exit circle at a, from node a's center
  double exit_b = 0.0;          // axial position of the exit circle at b, from node b's center (toward a)
  Circle circle_a, circle_b;    // exit circles; normals point away from their node along the beam
  // Where along the frustum (0: exit plane a, 1: exit plane b) the B-rep cuts the beam between two separately
  // built pieces. Halfway by default: a place that commutes with similarities and lies outside both nodes.
  // Trimming moves it on beams between two boundary hubs, to a place clear of the body's boundary.
  double cut_fraction = 0.5;
  // Axial length of the frustum between the two exit planes.
  double length() const { return cone.length - exit_a - exit_b; }
  // The cut's axial position from node a's center.
  double cut_position() const { return exit_a + cut_fraction * length(); }
  // The cut circle, normal along the beam (from a to b).
  Circle cut_circle() const;
};

struct FlatLattice;
// The frustums of every beam of a listing (parallel).
std::vector<BeamFrustum> beam_frustums(const FlatLattice& lattice);

// node_a, node_b: the node balls; ra, rb: the beam's end radii (<= the node radii).
BeamFrustum beam_frustum(const Ball& node_a, const Ball& node_b, double ra, double rb);

// Volume of the frustum between the exit planes (closed form pi h (r1^2 + r1 r2 + r2^2) / 3).
double frustum_volume(const BeamFrustum& f);

// Volume of the spherical cap of a ball of radius `radius` beyond the plane at signed distance `plane_position`
// from its center: pi h^2 (3R - h) / 3 with h = R - plane_position.
double spherical_cap_volume(double radius, double plane_position);

}  // namespace steady
