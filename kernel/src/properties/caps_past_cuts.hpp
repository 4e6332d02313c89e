#pragma once
// The caps of a node ball beyond its hub's cut disks. A beam shorter than its two balls (the lattice is not clean
// there) has each ball reach past its mid-plane cut: hub_properties ends the hub at the cut disk, the ball's cap
// beyond it being the beam's far half's, while the hub's Fuse (hub_union.cpp) keeps its ball whole. The Fuse is
// compared with, and the cluster's correction takes away, the hub's exact properties plus these caps.
#include <string>

#include "steady/lattice/hub.hpp"
#include "steady/properties/mass_moments.hpp"

namespace steady {

// The moments (about the node center) of what the Fuse's whole ball adds to the hub of hub_properties: the parts of
// the ball beyond its stumps' cut planes (spherical caps, in closed form), less where hub_properties keeps them (in
// the directions in which the cut disk lies inside a neighbouring stump, whose exit cap overlaps this stump's:
// integrated over the cap's meridians). When two caps meet, `refusal` says so and the moments are not to be used.
MassMoments caps_past_cuts(const Hub& h, std::string& refusal);

}  // namespace steady
