#pragma once
// Integral properties of a whole lattice (volume, outer area, centroid, inertia tensor) in closed form from
// row and slab sums, exact for clean lattices (hubs of different nodes with disjoint interiors).
//
// The lattice is the union of its hubs. With the node center as origin, a hub is its ball plus each stump's
// part outside the ball, those parts being disjoint unless caps overlap; so
//     lattice = sum over balls + sum over beams (both stumps, each as if alone) + sum over hubs of the
//               overlap correction (zero unless two stumps of the hub overlap outside its ball).
// Each term is a solid's moments, which similar copies map linearly (similar_copies.hpp):
//   * balls are steady along i, j and k: per template node, sum_k W^k sum_j V^j sum_i U^i of one ball;
//   * the beams of pattern (n1, di, dj, dk, n2) are steady along k (always), along j when dk = 0 or V and W
//     commute, along i when moreover U commutes with V (dj != 0) and W (dk != 0); a pattern therefore costs
//     O(1), O(u) or O(uv) beam evaluations, each in the pattern's own index range (the borders are exact);
//   * overlap corrections are summed by hub class: per direction a hub is either at a border (its own
//     class, for it misses the beams that would leave the lattice) or interior (one class, summed in closed
//     form); directions along which a hub's beams are not steady are enumerated.
// Omitted nodes are exceptions: their balls, the beams they kill and the changed hubs around them are
// subtracted and re-added exactly. The moments are taken about a reference point in the middle of the
// lattice, so that the central inertia does not lose digits to a far origin.
#include <cstdint>
#include <string>

#include "steady/properties/hub_properties.hpp"
#include "steady/lattice/lattice.hpp"
#include "steady/properties/mass_moments.hpp"
#include "steady/core/progress.hpp"

namespace steady {

struct LatticePropertiesOptions {
  HubPropertiesOptions hub;
  // Run the clean check first. Hubs of different nodes that overlap are reported and, with union_overlaps,
  // their exact union replaces their sum (hub_union.hpp); without, a non-clean lattice is refused.
  bool check_clean = true;
  bool union_overlaps = true;
};

struct LatticeProperties {
  double volume = 0.0;
  double area = 0.0;        // outer surface (the cut disks between hubs are inside the lattice)
  Vec3 centroid{0.0};
  Mat3 inertia{0.0};        // about the centroid, density 1
  MassMoments moments;      // about `reference`
  Vec3 reference{0.0};
  // Work done: beam shapes and hub shapes evaluated (the rest came from the series), and hub shapes whose
  // caps overlap (integrated by quadrature).
  std::int64_t beam_shapes = 0;
  std::int64_t hub_shapes = 0;
  std::int64_t overlapping_hub_shapes = 0;
  // The clean check's verdict: verified false when the lattice was too large to check (or not asked).
  bool clean_verified = false;
  // Overlapping hubs of different nodes (pairs found), and their exact union: beams whose cut moved past a
  // crowded hub's collars when that was enough (no Boolean), else clusters and hubs fused and the integration's
  // error estimate relative to the clusters' volume. overlap_description names the first few.
  std::int64_t overlap_count = 0;
  std::int64_t moved_cuts = 0;
  std::int64_t union_clusters = 0;
  std::int64_t union_hubs = 0;
  double union_error = 0.0;
  std::string overlap_description;
};

// Closed form from row and slab sums, plus the exact union of overlapping hubs when the lattice is not clean.
// Throws InvalidInput naming the overlapping hubs when the lattice is not clean and union_overlaps is off,
// ResourceLimit when more than kMaxUnionHubs hubs overlap or the moments overflow doubles, Cancelled when the
// progress callback asks to stop.
LatticeProperties lattice_properties(const Lattice& lattice, const LatticePropertiesOptions& options = {},
                                     Progress& progress = no_progress());

// The brute-force twin: every hub of the lattice built with hub() and summed. O(balls). No clean check.
LatticeProperties lattice_properties_brute_force(const Lattice& lattice, const LatticePropertiesOptions& options = {});

// Centroid and inertia from moments about a reference point.
LatticeProperties properties_from_moments(const MassMoments& about_reference, const Vec3& reference);

}  // namespace steady
