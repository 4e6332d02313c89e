#pragma once
// Elements that meet foreign ones (query/foreign_contacts.hpp) in the B-rep. No hub-by-hub construction holds
// there, and the properties already measure such lattices by fusing the overlapping hubs. The B-rep does the same: the hubs of
// every element in a contact are built as one group (hub_group.hpp), each member closed by collars on its
// stumps and the group fused once. A beam in a contact belongs whole to its group (both its balls join, and its
// two stumps meet at the middle of its free length); a beam leaving a group is free of contacts, so its stump ends
// a quarter of the way along its free length, and the beam runs on from that collar as from a crowded hub's.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "brep/hub_core.hpp"
#include "lattice/hub_collars.hpp"
#include "query/foreign_contacts.hpp"
#include "steady/lattice/beam_frustum.hpp"
#include "steady/lattice/flat_lattice.hpp"

namespace steady {

// A group member's stumps in its canonical frame (unit ball at the origin, turned by the transpose of `rotation`,
// the hub's placement in the catalog), in the order of `stumps` ((beam, end) pairs, as the builder lists a hub's
// stumps). The canonical frame matters: the cores' arrangement chooses its sphere's seam among directions that
// the world's axes can hit exactly in a symmetric lattice (an FCC or BCC built in world axes failed there).
std::vector<CoreStump> member_stumps(const FlatLattice& f, const std::vector<BeamFrustum>& frustums, std::int64_t ball,
                                     const std::vector<std::pair<std::int64_t, int>>& stumps, const Mat3& rotation);

// A ball with no beam as a group member: the unit sphere, closed, with no collar.
std::shared_ptr<const HubCore> lone_ball_core();

// The kind of core a member is built as: the hull model's arrangement when every beam is tangent to the ball, else
// transversal stumps.
CoreKind member_kind(const std::vector<CoreStump>& stumps);

// Where a member's stump ends along its beam, measured from the member's ball center: `here` is where the stump
// runs free of its hub (its exit circle or its core's collar), `there` the same from the other ball, `length` the
// distance between the two centers. A beam inside the group (`inner`) is covered by its two stumps, which meet at
// the middle of its free length (touching disks fuse more reliably than two stumps overlapping on one cone), or
// already overlap (a beam too short for its hubs); a beam leaving the group keeps three quarters of its free
// length, so that two groups at its ends stay apart.
double member_collar(double here, double there, double length, bool inner);

}  // namespace steady
