#pragma once
// Constant-radius lattices (Kurzeja's dissertation, 4.5.3 and 5.4.2): every beam becomes a rod of one radius rho,
// and every node a connector that holds the rods ending there,
//     Connector = Ball(node, reach rho) ∩ ExtendedHub(sleeve rho) − ExtendedHub(hole rho),
// where ExtendedHub(s) is the union of the whole beams at the node as capsules of radius s (cylinders to the
// neighbours and their end balls; here the node's ball is core_bulge larger, see below). A connector depends only on its node's beam directions (the radius is the same
// everywhere, and a beam longer than the reach leaves the ball before it ends), so connectors of nodes whose
// direction sets agree up to a rotation are congruent: one family, one part made many times. Similar hubs of a
// steady lattice (BeCOTS lattices included) have the same directions up to a rotation, so they share a family.
//
// This is the plan (no OpenCASCADE): the families with every member's rigid placement, and the rods with their
// cut lengths. steady/brep/connectors.hpp builds the solids.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "steady/core/vec.hpp"
#include "steady/lattice/flat_lattice.hpp"

namespace steady {

struct ConnectorParameters {
  double rod_radius = 0.0;  // rho, in model units (> 0)
  double sleeve = 1.6;      // outer radius of the sleeves, in rod radii (> hole)
  double reach = 2.5;       // radius of the ball bounding the connector, in rod radii (> sleeve)
  double hole = 1.0;        // radius of the holes the rods go in, in rod radii (>= 1, so that a rod fits)
  // The node balls of the two extended hubs are this much (relative) larger than their cylinders, in [0.01, 0.5].
  // With equal radii (the dissertation's capsules) each cylinder is tangent to the ball along a circle, and two
  // nearly opposite cylinders graze each other there: OpenCASCADE's Booleans then return anything (a kagome
  // node of a curved BeCOTS lattice, beams 0.19 degrees from opposite: volumes 41 to 81 rod radii^3 for one
  // shape). 5 % larger balls meet every cylinder at 18 degrees, and the cylinders can start inside the ball,
  // where they do not meet. The connector keeps its arms and holes; its core is a ball 5 % wider.
  double core_bulge = 0.05;
  // Nodes whose beam directions agree to this angle (radians) up to a rotation share a family; members are then
  // placed copies of the first, off by at most about this angle times the reach.
  double angle_tolerance = 1e-9;
  // Rods whose lengths differ by at most this (model units) share a cut-list entry; 0 means 1e-9 rod radii.
  double length_tolerance = 0.0;
};

// world point = center + rotation * template point (a proper rotation: the template is never mirrored).
struct ConnectorPlacement {
  std::int64_t ball = -1;
  Mat3 rotation{1.0};
  Vec3 center{0.0};
};

struct ConnectorFamily {
  // Unit beam directions of the family's template, in its own frame: the first is +z, the first one not
  // parallel to it lies in the xz-plane (x > 0).
  std::vector<Vec3> directions;
  std::vector<ConnectorPlacement> members;  // the first is the node the template was taken from
};

// One rod per beam: it runs on the beam's axis from `start` to `end`, inside both connectors' holes up to where it
// would meet another rod of the same node (depth_a, depth_b from the node centers).
struct Rod {
  std::int64_t beam = -1, a = -1, b = -1;  // the beam and its two balls
  Vec3 start{0.0}, end{0.0};
  double length = 0.0;    // what to cut
  double depth_a = 0.0, depth_b = 0.0;
  double exposed = 0.0;   // visible between the two connectors (along the hole's wall)
};

struct RodLength {
  double length = 0.0;              // the longest rod of the entry (cut to this, within length_tolerance)
  std::vector<std::int64_t> rods;   // indices into ConnectorPlan::rods
};

struct ConnectorPlan {
  ConnectorParameters parameters;
  std::vector<ConnectorFamily> families;
  std::vector<int> family_of_ball;  // -1 for a ball without beams (it gets no connector)
  std::vector<int> member_of_ball;  // index in its family's members, -1 without beams
  std::vector<Rod> rods;            // one per beam, in beam order
  std::vector<RodLength> cut_list;  // by increasing length
  std::int64_t isolated_balls = 0;
  // The reaches (rod radii) that would work for this lattice with this sleeve and hole: above min_reach every
  // sleeve holds its rod beyond the rod's end; below max_reach every beam keeps its two connectors apart.
  double min_reach = 0.0, max_reach = 0.0;
};

// Throws InvalidInput naming the parameter (rod_radius, sleeve, reach, hole, core_bulge, angle_tolerance,
// length_tolerance)
// when it is not finite or out of its range.
void check_connector_parameters(const ConnectorParameters& parameters);

// The depth (from the node center, along the rod) where rod `slot` of a node with unit beam directions
// `directions` ends so that it meets none of the node's other rods of radius `rod_radius`: each pair is split by
// its bisector plane, rho cot(theta / 2) for two rods at angle theta. 0 for a node of degree 1.
double rod_end_depth(const std::vector<Vec3>& directions, std::size_t slot, double rod_radius);

// The reaches (rod radii) that fit the lattice with the other parameters (their reach is not used): (min_reach,
// max_reach) as ConnectorPlan has them; empty (min >= max) when none does. Throws as plan_connectors does, except
// about the reach.
std::pair<double, double> connector_reach_range(const FlatLattice& lattice, const ConnectorParameters& parameters);

// The families and rods of the constant-radius version of `lattice` (its ball radii and beam radii are not used:
// only centers and beams). Throws InvalidInput naming "reach" when the sleeves end before the rods do at some node
// (naming the node and the smallest reach that holds every rod) or a beam is too short to keep its two connectors
// apart (naming the beam, its balls, its length and the largest reach that fits), and naming "lattice" when a beam
// has zero length or two beams of a node leave it in the same direction.
ConnectorPlan plan_connectors(const FlatLattice& lattice, const ConnectorParameters& parameters);

}  // namespace steady
