#pragma once
// Where to put a sphere's seam (the half great circle from pole to pole at u = 0) so that a face bounded by given
// loops stays portable: no loop runs across the seam and back (portable_sphere_faces.hpp). Either the seam and
// poles keep clear of every loop, or the seam crosses some loops once each, transversally and away from their
// vertices: a loop around a pole (which readers keep, as the hub cores do, hub_core.cpp).
#include <gp_Dir.hxx>

#include <vector>

namespace steady {

// A point along a loop of the face: its direction from the sphere's centre, and the edge (index in the loop) and
// the edge's parameter there.
struct LoopSample {
  gp_Dir d;
  int edge = 0;
  double t = 0.0;
};
using SampledLoop = std::vector<LoopSample>;  // closed: the last sample is followed by the first

// Where the seam crosses a loop: between its samples `at` and `at + 1` (on one edge).
struct SeamCrossing {
  int loop = 0;
  int at = 0;
};

struct SeamFrame {
  double clearance = -1.0;  // radians between the seam (and poles) and the loops, away from the crossings
  gp_Dir pole, seam;        // the frame's Z (north pole) and X (the seam's direction at the equator)
  std::vector<SeamCrossing> crossings;
};

// Frames whose clearance is at least `min_clearance`, best first: those whose seam crosses no loop, by clearance,
// then those whose seam crosses loops once each. Poles at 97 Fibonacci points of a half sphere (the other half
// gives the same seams), 72 seam directions each, the best kept per pole.
std::vector<SeamFrame> ranked_seam_frames(const std::vector<SampledLoop>& loops, double min_clearance);

}  // namespace steady
