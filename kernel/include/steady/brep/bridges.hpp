#pragma once
// Bridges: the trim policy Bridge (conformal-microstructures.md, "whole tiles and bridging tiles").
//
// Only the hubs that lie whole inside the wall are kept (as policy Whole keeps them: ball and half-beams clear of
// it). A kept hub that lost a neighbour (a beam whose other hub is not kept) gets one bridge: a beam from its node
// toward the nearest point of the wall (the body's boundary, or with a skin the skin's inner boundary), with the
// largest end radius at that node among the beams it lost, ending at a node of that radius just past the wall.
// The bridged lattice (kept hubs, the beams between them, the bridges and their far nodes) is then trimmed with
// policy Clip: the wall cuts only bridges, never a kept hub's ball or beams, and with a skin the cut bridges are
// united with it. Being a lattice, the bridged part goes through the same builder, Booleans, retries and checks.
//
// Decisions where the geometry leaves the method no answer:
//  - a hub on the medial axis (several nearest points, as on a cylinder's axis): the first point BRepExtrema
//    gives is taken, and counted as ambiguous (unless that bridge is blocked and rerouted);
//  - a bridge whose beam would meet another kept element (a ball or beam not of its own hub, or a bridge already
//    made): the builder needs elements that meet only at their own hubs, so the bridge is rerouted. Once every
//    nearest-point bridge that is clear has been made (in hub order), each blocked hub tries, in hub order, the
//    directions of the beams it lost and rings of directions about its nearest one (a fixed number: at most 80,
//    brep/bridge_routes.hpp), each followed by a ray to the wall, and takes the shortest route clear of the same
//    capsule tests (ties: the earlier candidate). Only when no route is clear is it left unbridged: counted as
//    blocked and named through TrimOptions::report; its hub stays joined to the lattice by its other beams.
// The policy's `dangling` option does not apply: the lost beams are always replaced by the bridges.
#include <TopoDS_Shape.hxx>

#include <cstdint>
#include <vector>

#include "steady/core/progress.hpp"
#include "steady/core/vec.hpp"
#include "steady/lattice/flat_lattice.hpp"

namespace steady {

struct Bridge {
  std::int64_t hub = 0;    // the kept hub, an index of the source lattice's balls
  Vec3 wall{0.0};          // the nearest point of the wall to the hub's node
  Vec3 end{0.0};           // the far node, past the wall on the line from the node through `wall`
  double radius = 0.0;     // of the bridge beam and its far node
  bool ambiguous = false;  // the node has several nearest points on the wall (and the first was taken)
  bool rerouted = false;   // the bridge toward the nearest point was blocked: `wall` is where another route, from
                           // the node along the line through `wall`, first meets the wall
};

struct BridgePlan {
  // Balls: the kept hubs (in the source's order), then one far node per bridge; beams: those between kept hubs,
  // then the bridges.
  FlatLattice lattice;
  std::vector<std::int64_t> kept;  // source ball index of lattice.balls[k] for k < kept.size()
  std::vector<Bridge> bridges;        // the nearest-point bridges in hub order, then the rerouted ones in hub order
  std::vector<std::int64_t> blocked;  // source hubs that lost a neighbour and found no clear route to the wall
  std::int64_t lost_neighbour_hubs = 0;
  std::int64_t inside_hubs = 0, outside_hubs = 0, crossing_hubs = 0;  // the source's hubs against the wall
};

// The bridged lattice of `lattice` in `body` with a skin of thickness `skin` (0: none). InvalidInput naming
// "body" (not one valid closed solid; the lattice misses it), "skin", or "policy" (no hub lies whole inside);
// Cancelled soon after `progress` is (it reports through the classification and the nearest points).
BridgePlan plan_bridges(const FlatLattice& lattice, const TopoDS_Shape& body, double skin,
                        Progress& progress = no_progress());

}  // namespace steady
