#pragma once
// The routes of bridges (the trim policy Bridge, steady/brep/bridges.hpp): the capsule tests every bridge must
// pass (clear of the kept elements of other hubs and of the bridges already made), and, for a hub whose bridge
// toward its nearest wall point fails them, other routes to the wall. The candidates are the directions of the
// beams the hub lost, then rings of directions about the nearest one at growing angles; each is followed by a ray
// to its first point on the wall, and the shortest route that passes the capsule tests is taken. The number of
// candidates per hub is fixed (at most kLostBeamRoutes + kRings x kRingDirections rays), so the search costs at
// most that many rays and capsule tests per blocked hub.
#include <IntCurvesFace_ShapeIntersector.hxx>

#include <cstdint>
#include <optional>
#include <vector>

#include "steady/brep/bridges.hpp"
#include "steady/brep/solid_body.hpp"
#include "steady/lattice/flat_lattice.hpp"

namespace steady::bridges {

// How far the far node lies past the wall, in bridge radii beyond its own radius, measured along the wall's
// normal: clear of a convex wall by half a radius, so the wall cuts the beam and not the node (at a concave wall
// part of the node may stay inside it).
constexpr double kFarNodeClearance = 0.5;

// The bounded search of a blocked hub: the directions of at most kLostBeamRoutes lost beams (in beam order),
// then kRings rings at kRingStepDegrees, 2 kRingStepDegrees, ... about the nearest direction, of kRingDirections
// directions each: at most 8 + 6 x 12 = 80 rays.
constexpr int kLostBeamRoutes = 8;
constexpr int kRings = 6;
constexpr double kRingStepDegrees = 10.0;
constexpr int kRingDirections = 12;
// A route meeting the wall farther than this from its normal is not taken: its cut at the wall would be a long
// sliver and its far node far along the wall.
constexpr double kMaxIncidenceDegrees = 60.0;

// The capsule tests: the bridge from a hub's node to its far node, of the bridge's radius (widened by `gap`),
// against every kept element of another hub (each inside the capsule of its largest radius: a beam is the hull
// of its end balls) and against other bridges.
class Clearance {
 public:
  Clearance(const FlatLattice& f, const std::vector<char>& kept, double gap) : f_(f), kept_(kept), gap_(gap) {}
  // Whether `b` meets a kept ball or beam not of its own hub (thread-safe).
  bool meets_kept_element(const Bridge& b) const;
  // Whether `b` meets one of `made`.
  bool meets_bridge(const Bridge& b, const std::vector<Bridge>& made) const;
  bool clear(const Bridge& b, const std::vector<Bridge>& made) const {
    return !meets_kept_element(b) && !meets_bridge(b, made);
  }

 private:
  const FlatLattice& f_;
  const std::vector<char>& kept_;
  double gap_;
};

// The directions tried for a hub whose nearest direction (unit, from its node toward its nearest wall point) is
// blocked, in the order that settles ties: `lost` (unit directions toward the neighbours it lost; the first
// kLostBeamRoutes), then the rings about `nearest`, each starting from a fixed axis perpendicular to it.
std::vector<Vec3> reroute_directions(const Vec3& nearest, const std::vector<Vec3>& lost);

// Rays from inside the wall to it (IntCurvesFace_ShapeIntersector, loaded once; serial).
class BridgeRouter {
 public:
  BridgeRouter(const FlatLattice& f, const SolidBody& wall);
  // `hub`'s bridge of radius `radius` along the unit `direction`: its wall point is where the ray from the node
  // first meets the wall, its far node past it (kFarNodeClearance along the wall's normal there). nullopt when the
  // ray misses the wall or meets it farther than kMaxIncidenceDegrees from its normal.
  std::optional<Bridge> route(std::int64_t hub, double radius, const Vec3& direction);
  // The shortest route among reroute_directions(nearest, lost) that is clear (Clearance::clear against `made`),
  // marked rerouted; nullopt when none is.
  std::optional<Bridge> reroute(const Bridge& nearest, const std::vector<Vec3>& lost, const Clearance& clearance,
                                const std::vector<Bridge>& made);

 private:
  const FlatLattice& f_;
  double reach_;  // longer than any ray inside the wall
  IntCurvesFace_ShapeIntersector rays_;
};

}  // namespace steady::bridges
