#pragma once
// How the boundary of one hub's sphere is parameterized as a single OpenCASCADE spherical face.
//
// OpenCASCADE's sphere (u, v) in [0, 2 pi] x [-pi/2, pi/2] has a seam (the half meridian u = 0) and two poles.
// The face is the sphere minus the beams' exit caps. We choose the frame (pole Z, seam direction X) so that the
// poles and the seam keep away from the circles, then every circle plays one of four roles:
//   Inner      - meets neither the seam nor a pole: a hole, one closed edge;
//   North/South - its cap holds a pole: it crosses the seam once and bounds the face at the top / bottom;
//   Straddle   - crosses the seam twice: split into a left arc (u near 0) and a right arc (u near 2 pi), both in
//                the outer wire, which runs up the right side of the domain and down the left side.
// The layout is computed once per distinct hub shape on the unit sphere, in the hub's canonical frame, and is
// invariant under similarities: so are the (u, v) curves of the circles, which are shared by all copies.
#include <vector>

#include "steady/brep/brep_builder.hpp"
#include "steady/core/vec.hpp"
#include "lattice/hub_catalog.hpp"

namespace steady {

enum class CircleRole { Inner, North, South, Straddle };

// A stretch of a circle's parameter on which u(t) is continuous, and which branch of the longitude it uses.
enum class ArcBranch {
  Inner,   // u in (0, 2 pi): the circle never crosses u = 0
  Left,    // u near 0, >= 0
  Right,   // u near 2 pi, <= 2 pi
  North,   // u increasing from 0 to 2 pi over the whole circle
  South,   // u decreasing from 2 pi to 0
};

struct CircleArc {
  double t0 = 0.0, t1 = 0.0;  // parameter range, t0 < t1
  ArcBranch branch = ArcBranch::Inner;
};

struct CircleLayout {
  SphereCap cap;
  Vec3 e1{1.0, 0.0, 0.0}, e2{0.0, 1.0, 0.0};
  double rho = 1.0;
  CircleRole role = CircleRole::Inner;
  // The circle's own vertices: its seam crossings (sorted, in [window, window + 2 pi)), or {0} for an inner
  // circle. Every other vertex put on the circle later is normalized into the same window.
  double window = 0.0;
  std::vector<double> own_vertices;
  std::vector<double> crossing_v;  // latitude v of each seam crossing, same order as own_vertices (not Inner)
  std::vector<CircleArc> arcs;     // partition of [window, window + 2 pi]

  Vec3 point(double t) const;
};

struct SphereLayout {
  Vec3 z{0.0, 0.0, 1.0}, x{1.0, 0.0, 0.0};  // pole and seam direction (orthonormal); y = z x x
  std::vector<CircleLayout> circles;         // same order as the caps
  int north = -1, south = -1;                // the circle holding each pole, or -1 (a degenerate pole edge)
  std::vector<int> straddles;                // straddling circles ordered by the latitude of their crossings
  double margin = 0.0;  // smallest angle (radians) between a pole or the seam's tangency and a circle

  // (u, v) of circle point p(t) on the branch of `arc`, and its first and second derivatives in t.
  void uv(int circle, ArcBranch branch, double t, double out[2], int derivative = 0) const;
};

// Below this margin (radians) a layout is refused: a pole or a near-tangent seam crossing would sit within
// 1e-4 sphere radii of a circle, closer than the approximations of the (u, v) curves can resolve cleanly.
constexpr double kMinimumLayoutMargin = 1e-4;

// Chooses the frame maximizing the margin over a fixed set of candidate poles and seam directions (the caps'
// axes and a Fibonacci covering of the sphere), ranking frames whose margin is at least kGoodLayoutMargin by
// their number of seam crossings. The caps must be pairwise disjoint. Throws InvalidInput when no frame reaches
// kMinimumLayoutMargin (a hub too crowded for a single spherical face).
SphereLayout layout_sphere(const std::vector<SphereCap>& caps,
                           SeamPreference preference = SeamPreference::FewestCrossings);

// Frames whose margin reaches this (about 1.7 degrees) are all good; among them fewer crossings win.
constexpr double kGoodLayoutMargin = 0.03;
// A frame without straddling circles is preferred to one with a larger margin down to this margin (radians).
constexpr double kPortableLayoutMargin = 3e-3;

}  // namespace steady
