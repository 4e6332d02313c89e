#pragma once
// Hub overlaps: a lattice is clean in the papers' sense when the hubs of different nodes have disjoint
// interiors; only then is the lattice the assembly of its hubs and its integral properties the sum of theirs.
// (The B-rep's clean check, clean_check.hpp, asks more: disjoint exit circles on every ball, so that the
// boundary needs no Boolean. Overlapping stumps of one hub are fine here: hub_properties integrates them.)
//
// A hub's pieces are convex: its ball, and each stump, the convex hull of the beam's end ball at the node and
// the cut disk. Two hubs overlap when a piece of one meets a piece of the other (the two stumps of one beam,
// which share their cut disk, excepted), decided by the distance between the pieces shrunk by 1e-9 of their
// size (GJK on support mappings): pieces that only touch are not reported. Candidate hub pairs come from a
// grid of hub bounding spheres. For lattices with more than kDirectHubOverlapCheckHubs hubs, the check runs on a
// window of k-slabs and relies on steadiness: hubs of slab k are W^k images of slab 0's, so every pair of
// hubs k-slabs apart is an image of a pair in the window, and slabs whose bounding boxes (the box of a slab
// mapped by W^delta) do not meet are never compared. Beyond kMaxHubOverlapCheckHubs the check is not run (verified = false).
#include <cstdint>
#include <string>
#include <vector>

#include "steady/lattice/lattice.hpp"
#include "steady/lattice/hub.hpp"
#include "steady/core/progress.hpp"

namespace steady {

// Up to here every hub is compared; beyond, the slab window.
constexpr std::int64_t kDirectHubOverlapCheckHubs = 400'000;
// The most hubs the check examines (about a minute on one core); beyond, it is not run.
constexpr std::int64_t kMaxHubOverlapCheckHubs = 20'000'000;

struct HubOverlap {
  NodeId a, b;
  std::string detail;  // which pieces: "ball" or "stump of beams[p]"
};

struct HubOverlapReport {
  bool verified = false;             // the whole lattice was checked
  std::int64_t overlap_count = 0;    // overlapping hub pairs found
  std::vector<HubOverlap> overlaps;  // the first max_reports of them
  std::int64_t hubs_checked = 0;
  bool clean() const { return verified && overlap_count == 0; }
  // "hubs (i,j,k,n) and (i,j,k,n) overlap (ball / stump of beams[p]); ..." for the first few.
  std::string describe(std::size_t max_listed = 5) const;
};

enum class HubOverlapCheckMethod {
  Automatic,   // every hub up to kDirectHubOverlapCheckHubs, the slab window beyond
  AllHubs,     // every hub (refused by the memory budget if too large)
  SlabWindow,  // the slab window, whatever the size (the tests compare it with AllHubs)
};

HubOverlapReport check_hub_overlaps(const Lattice& lattice, std::size_t max_reports = 100, Progress& progress = no_progress(),
                        HubOverlapCheckMethod method = HubOverlapCheckMethod::Automatic);

// Whether two hubs of different nodes overlap (the test above, on hubs as given: their cuts may have moved), and
// which pieces ("stump of beams[p] / ball") in `detail`.
bool hubs_overlap(const Hub& a, const Hub& b, std::string* detail = nullptr);

// Whether the cut disk of stump `stump` meets another stump of its hub. A cut moved into the ball must not: the hub
// would keep what the other stump holds beyond the disk, which the beam's far half holds too.
bool cut_disk_meets_other_stumps(const Hub& h, std::size_t stump);

// Brute force over every pair of hubs and pieces: for the tests.
HubOverlapReport check_hub_overlaps_brute_force(const Lattice& lattice, std::size_t max_reports = 100);

std::string to_string(const NodeId& id);

}  // namespace steady
