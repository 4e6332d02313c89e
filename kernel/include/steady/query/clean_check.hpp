#pragma once
// The clean check: may a lattice be turned into a B-rep with no Boolean at all?
//
// A lattice is clean when
//   1. on every ball, the exit circles of its beams are pairwise disjoint (their caps on the sphere do not meet);
//   2. no two balls meet, except a ball nested inside a neighbour through a degenerate beam (one end ball of the
//      beam containing the other) and carrying no other beam: it is absorbed;
//   3. no ball meets a beam that is not incident to it;
//   4. no two beams that share no ball meet.
// Then the boundary is exactly: per ball a sphere with one circular hole per beam, per beam one cone between its
// two exit circles. Beams sharing a ball need no test of their own: a cone whose axis passes through the ball's
// center narrows, as seen from that center, as it goes out, so it stays inside the angular cone of its exit cap;
// disjoint caps therefore keep the stumps apart.
//
// "Meet" means: closer than kCleanRelativeGap times the smaller radius involved (kCleanAngularGap for caps), so
// that every edge of the B-rep stays far above OpenCASCADE's tolerances.
#include <cstdint>
#include <string>
#include <vector>

#include "steady/lattice/beam_frustum.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/lattice.hpp"

namespace steady {

// Elements closer than this fraction of the smaller radius involved count as meeting. OpenCASCADE's confusion
// tolerance is 1e-7 model units; at the 0.1 to 10 mm radii of printed lattices, 1e-6 relative keeps every gap
// at least an order of magnitude above it.
constexpr double kCleanRelativeGap = 1e-6;

enum class CleanIssueKind {
  CircleOverlap,  // two exit circles on one ball meet (ball, beam, other_beam)
  BallBall,       // two balls meet (ball, other_ball)
  BallBeam,       // a ball meets a beam not incident to it (ball, beam)
  BeamBeam,       // two beams with no common ball meet (beam, other_beam)
};
const char* to_string(CleanIssueKind kind);

struct CleanIssue {
  CleanIssueKind kind = CleanIssueKind::CircleOverlap;
  std::int64_t ball = -1, other_ball = -1;
  std::int64_t beam = -1, other_beam = -1;
  std::string describe() const;
};

struct CleanReport {
  std::int64_t issue_count = 0;          // all issues found
  std::vector<CleanIssue> issues;        // the first max_reported of them, sorted by kind, then indices
  std::vector<std::int64_t> absorbed_balls;    // balls nested in a neighbour through a degenerate beam
  std::vector<std::int64_t> degenerate_beams;  // beams with no part outside their nodes (one end ball contains
                                               // the other, or the nodes overlap past the exit planes)
  std::int64_t candidate_pairs = 0;      // pairs the broad phase passed on to exact tests (for the benchmark)
  bool clean() const { return issue_count == 0; }
};

struct CleanCheckOptions {
  std::int64_t max_reported = 10000;  // issues kept in the report (all are counted)
  // Leave out overlapping exit circles (rule 1): the B-rep builder builds such hubs from cores (hub_core.hpp).
  bool skip_circle_overlaps = false;
};

CleanReport check_clean(const FlatLattice& lattice, const CleanCheckOptions& options = {});

// What the builders (B-rep, mesh) require: no element meeting a foreign one (overlapping exit circles on one ball
// are crowded hubs, which they build). Throws InvalidInput ("lattice") naming the first offenders otherwise.
void require_clean_for_build(const FlatLattice& lattice);

// Per ball: nested in a neighbour through a degenerate beam and carrying only degenerate beams (rule 2 above).
std::vector<char> absorbed_balls(const FlatLattice& lattice, const std::vector<BeamFrustum>& frustums);
CleanReport check_clean(const Lattice& lattice, const CleanCheckOptions& options = {});

// The slow twin (tests): every pair of elements is tested exactly, no broad phase.
CleanReport check_clean_brute_force(const FlatLattice& lattice);

}  // namespace steady
