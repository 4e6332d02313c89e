#pragma once
// The volume that overlapping hubs share, by sampling only where their pieces meet: the independent check of
// OpenCASCADE's Fuse of a cluster of hubs (hub_union.cpp) and of the B-rep's Fuse of a group of closed cores
// (brep/hub_group.cpp). Sampling the whole box, as before, left a standard error of about 1e-3 of the cluster's
// volume, and a Fuse 1.4e-3 off passed it (docs/brep.md); the shared volume lives in a small part of that box, so
// lines through it measure it far more closely.
#include <cstdint>
#include <utility>
#include <vector>

#include "steady/lattice/hub.hpp"

namespace steady {

// A box around the hubs: their balls and cut disks (each disk boxed by its radius, which is enough).
std::pair<Vec3, Vec3> hubs_bounds(const std::vector<Hub>& hubs);

// How a hub is read as a solid. Whole: its ball and its stumps (the hull of the beam's end ball and the stump's cut
// disk). Closed at its cuts: the same, except that what lies in a stump's cone beyond its cut disk is never the
// hub's, even inside the ball: a B-rep core closed by its collar disks (brep/hub_group.cpp), whose tight collar may
// lie inside the ball while another stump reaches through its disk.
enum class HubReading { Whole, ClosedAtCuts };

// Whether p lies in the hub read as `reading` says.
bool inside_hub(const Hub& h, const Vec3& p, HubReading reading = HubReading::Whole);

// The integral over space of (number of hubs holding p - 1, where positive): the sum of the hubs' volumes less the
// volume of their union. Integrated in the boxes where a piece (ball or frustum) of one hub meets a piece of
// another, each point weighted by how many of those boxes hold it: exactly along lines parallel to z (between the
// line's crossings of the pieces' quadrics, planes and the boxes' faces), over the lines' (x, y) by replicates of a
// jittered grid, about `lines` lines in all (a fixed seed, so runs repeat). Returns the estimate and its standard
// error (the replicates' spread).
std::pair<double, double> sampled_shared_volume(const std::vector<Hub>& hubs, int lines, std::uint64_t seed,
                                                HubReading reading = HubReading::Whole);

}  // namespace steady
