#pragma once
// Hubs: a ball plus its half-beams (stumps), the unit of geometry and of integral properties.
//
// A beam is the convex hull of two balls (a, ra) and (b, rb): in the papers' model these are its nodes,
// in the explicit-radii model they are smaller balls at the node centers. Its lateral surface is the
// cone tangent to both balls. The cone meets the sphere of a node of radius R >= r at the end
//     x = r sin(phi) + cos(phi) sqrt(R^2 - r^2)        along the axis from the node center,
// with sin(phi) = (r - r_other) / |ab|: a transversal circle when R > r, the tangent circle when R = r.
// The stump of a node ends at the beam's cut: the plane orthogonal to the axis halfway between the two
// node centers (it commutes with similarities, so similar hubs have similar stumps).
#include <vector>

#include "steady/core/ball.hpp"
#include "steady/lattice/lattice.hpp"

namespace steady {

// Two exit caps on a sphere closer than this angle (radians) count as meeting (the clean check's
// relative gap, on the sphere).
constexpr double kCleanAngularGap = 1e-6;

struct Circle {
  Vec3 center{0.0};
  Vec3 normal{0.0, 0.0, 1.0};  // unit; for beam circles it points along the beam, away from the node
  double radius = 0.0;
};

// The convex hull of two balls seen as a cone: axis, length, half-angle and the radius along the axis.
struct BeamCone {
  Vec3 a{0.0}, b{0.0};  // ball centers
  double ra = 0.0, rb = 0.0;
  Vec3 axis{0.0, 0.0, 1.0};  // unit, from a to b
  double length = 0.0;
  double sin_phi = 0.0;  // (ra - rb) / length: the cone narrows from a to b when positive
  double cos_phi = 1.0;

  // False when one ball contains the other (|ra - rb| >= length): the hull is then just the larger ball.
  bool has_lateral_surface() const { return length > 0.0 && std::abs(ra - rb) < length; }
  // Radius of the cone at axial position x from a (valid between the two tangent circles and beyond).
  double radius_at(double x) const { return (ra - x * sin_phi) / cos_phi; }
  // The circle where the cone touches ball (a, ra) / ball (b, rb).
  Circle tangent_circle_a() const;
  Circle tangent_circle_b() const;
};

BeamCone beam_cone(const Ball& a, const Ball& b);

// Axial position (from the center of the end ball, toward the other end) where the beam's cone leaves
// the sphere of radius `node_radius` around that end: node_radius >= the beam's radius there.
double cone_exit_position(const BeamCone& cone, bool at_a, double node_radius);

// One half-beam of a hub.
struct Stump {
  BeamId beam;
  std::int64_t beam_index = -1;  // index into Lattice::beams()
  bool at_start = true;          // the hub's node is the beam's start (ball a) or its end (ball b)
  BeamCone cone;                 // oriented from the hub's node toward the other node
  Circle on_node;                // where the cone leaves the node's sphere (normal along the beam)
  Circle cut;                    // the stump's end disk, on the mid-plane
  double exit_position = 0.0;    // axial position of on_node from the node center
  double cut_position = 0.0;     // axial position of the cut (half the beam length)
};

// Moves the stump's cut disk to axial position `position` from the node (the beam's mid-plane by default): a
// crowded hub whose stumps meet beyond the mid-plane keeps all of that meeting when its cuts move past it.
void move_cut(Stump& stump, double position);

struct Hub {
  NodeId node;
  std::int64_t ball_index = -1;
  Ball ball;
  std::vector<Stump> stumps;
};

// The beams incident to a node, as (beam, node is its start). Existing beams only. O(patterns).
std::vector<std::pair<BeamId, bool>> incident_beams(const Lattice& lattice, const NodeId& node);

// The hub of an existing node.
Hub hub(const Lattice& lattice, const NodeId& node);

}  // namespace steady
