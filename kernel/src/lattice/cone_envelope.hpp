#pragma once
// The hull model of a hub, without OpenCASCADE: the unit ball with one cone per stump, each tangent to the ball.
// On each cone, the hull's surface runs from the stump's tangent circle up to the envelope where another stump
// (or the ball) takes over. The same holds for a ball of radius R > 1 whose stumps are all tangent to the unit
// sphere inside it (beams whose end radius at this node is the same for all, scaled to 1): each cone then leaves
// the ball at v = sqrt(R^2 - 1), its exit_v, instead of at its tangent circle. This file finds that envelope exactly: along each generator of cone i, the first point
// where no other stump dominates, and around the cone the pieces where one stump (or the ball) stays the active
// neighbour, with their shared vertices. The B-rep hub core (brep/hub_core.cpp) turns the arrangement into faces;
// docs/brep.md explains the construction.
#include <vector>

#include "steady/core/vec.hpp"

namespace steady::hull {

// Two envelope values closer than this are tied (ties go to the cone with the lower index, then to cones over
// the sphere, so the faces on both sides of an edge agree).
constexpr double kTie = 1e-12;
// Vertices of the arrangement closer than this (unit-ball lengths) are the same vertex.
constexpr double kVertexMerge = 1e-8;
// A collar must clear the other stumps, and the envelope must stay below it, by this much (unit-ball lengths):
// thinner bands of cone between the envelope and the collar make sliver faces that the Booleans of trimming fail
// to split (docs/brep.md, "hub cores").
constexpr double kCollarClearance = 0.02;
// The envelope is checked against the collars at this many generators, besides its breakpoints.
constexpr int kEnvelopeProbes = 256;

// A cone tangent to the unit sphere along its circle at height s: points s d + (c - v s) r(u) + v c d with
// r(u) = cos u e + sin u f, c = cos(phi), s = sin(phi). v = 0 is the tangent circle; w(x) is the v of the
// plane through x orthogonal to d. |point(u, v)|^2 = 1 + v^2, so the cone leaves the ball of radius R at
// exit_v = sqrt(R^2 - 1), the same v for every cone of a hub (0 in the hull model, R = 1).
struct Cone {
  Vec3 d{0.0, 0.0, 1.0}, e{1.0, 0.0, 0.0}, f{0.0, 1.0, 0.0};
  double s = 0.0, c = 1.0;
  double exit_v = 0.0;
  Vec3 point(double u, double v) const;
  double w(const Vec3& x) const;
  double u_of(const Vec3& x) const;
};

// The cone of a stump leaving along `direction` (any length) with sin(phi) = sin_phi, leaving the ball at exit_v.
Cone make_cone(const Vec3& direction, double sin_phi, double exit_v = 0.0);

// On cone i along generator u, stump j dominates (w_j > w_i) below v = t (Lower), above it (Upper), along the
// whole generator (Never: i never dominates j there) or nowhere (Always: i always does).
struct Bound {
  enum Kind { Lower, Upper, Always, Never } kind = Always;
  double t = 0.0;
};
Bound bound_from(const Cone& ki, const Cone& kj, double u);

// Where cone i's generator u leaves the region dominated by others: the active neighbour (-1: none, the ball
// bounds it at v = exit_v) and the envelope's v there.
struct Active {
  int index = -1;
  double v = 0.0;
};
Active envelope_at(const std::vector<Cone>& cones, int i, double u);

// The lowest v along generator u above which another stump dominates again (infinity when none; -infinity when
// a stump dominates the whole generator).
double ceiling_at(const std::vector<Cone>& cones, int i, double u);

// Generators u in [0, 2 pi) where the active neighbour of cone i can change (sorted, distinct): where a bound
// crosses the exit circle, switches between lower and upper, or where three cones meet.
std::vector<double> breakpoint_candidates(const std::vector<Cone>& cones, int i);

// One arc of the envelope with a constant active neighbour: u from u0 to u1 (u1 - u0 = 2 pi for a closed arc)
// between vertices v0 and v1 (ids in the arrangement's vertex list).
struct Piece {
  int active = -1;
  double u0 = 0.0, u1 = 0.0;
  int v0 = -1, v1 = -1;
};

// The envelope of one cone: its pieces in increasing u, the first starting at u = window.
struct Envelope {
  double window = 0.0;
  std::vector<Piece> pieces;
};

// Vertices shared by all faces, merged by position (kVertexMerge).
struct VertexPool {
  std::vector<Vec3> points;
  int find_or_add(const Vec3& p);
};

// The envelopes of all cones with their shared vertices. v_collar[i] is the collar's v on cone i: the envelope
// must stay below it and every ceiling above it (by `clearance`: kCollarClearance, or less for tight collars, see
// CollarFit), else the hub is refused with a message.
// Closed pieces (one neighbour all around) get their vertex on the lower index's face; the partner starts there.
struct Arrangement {
  VertexPool vertices;
  std::vector<Envelope> envelopes;
};
Arrangement arrange_envelopes(const std::vector<Cone>& cones, const std::vector<double>& v_collar,
                              double clearance = kCollarClearance);

}  // namespace steady::hull
