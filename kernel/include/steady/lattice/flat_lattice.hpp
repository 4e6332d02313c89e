#pragma once
// The explicit list of a lattice's balls and beams with their incidence: what the B-rep builder, the clean
// check and trimming iterate over. It is built once (in parallel) from a Lattice and costs 48 bytes per ball
// plus 48 per beam; indices are the lattice's stable ball and beam indices.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "steady/core/ball.hpp"
#include "steady/lattice/lattice.hpp"

namespace steady {

// A beam as indices of its two node balls and its two end radii (the radii of the balls whose convex hull
// is the beam; equal to the node radii in the hull model).
struct FlatBeam {
  std::int64_t a = 0, b = 0;
  double ra = 0.0, rb = 0.0;
};

struct FlatLattice {
  std::vector<Ball> balls;
  std::vector<FlatBeam> beams;
  // Beams incident to ball i: incidence[incidence_offsets[i] .. incidence_offsets[i+1]), in increasing beam
  // index (so similar hubs of a steady lattice list their stumps in the same order).
  std::vector<std::int64_t> incidence_offsets;
  std::vector<std::int64_t> incidence;

  std::int64_t ball_count() const { return static_cast<std::int64_t>(balls.size()); }
  std::int64_t beam_count() const { return static_cast<std::int64_t>(beams.size()); }
  std::int64_t degree(std::int64_t ball) const { return incidence_offsets[ball + 1] - incidence_offsets[ball]; }
  const std::int64_t* incident_begin(std::int64_t ball) const { return incidence.data() + incidence_offsets[ball]; }
  const std::int64_t* incident_end(std::int64_t ball) const { return incidence.data() + incidence_offsets[ball + 1]; }
  // Where `beam` is among the beams incident to `ball` (degree(ball) when it is not one of them).
  std::int64_t incident_slot(std::int64_t ball, std::int64_t beam) const {
    return std::find(incident_begin(ball), incident_end(ball), beam) - incident_begin(ball);
  }
  // The node ball at the other end of `beam`, seen from `ball`.
  std::int64_t other_ball(std::int64_t beam, std::int64_t ball) const {
    return beams[beam].a == ball ? beams[beam].b : beams[beam].a;
  }
};

// Lists every ball and beam of the lattice (refuses, with ResourceLimit, listings beyond the memory budget).
FlatLattice flatten(const Lattice& lattice);

// Builds the incidence of explicit balls and beams; validates them (finite centers, radii > 0, beam end radii in
// (0, node radius], indices in range, no beam from a ball to itself) with InvalidInput naming the element.
FlatLattice make_flat_lattice(std::vector<Ball> balls, std::vector<FlatBeam> beams);

}  // namespace steady
