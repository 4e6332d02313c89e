#pragma once
// The brute-force twin of the ball-interference queries, shared by the kernel tests: every ball and beam the
// lattice lists (Lattice::for_each_ball/beam, evaluated once, optionally only those a mask keeps), tested
// one by one with the exact predicates. Slow and obviously right.
#include <cstdint>
#include <vector>

#include "steady/lattice/lattice.hpp"
#include "steady/query/interference.hpp"
#include "steady/query/lattice_query.hpp"

namespace steady::test {

struct BruteForceQuery {
  std::vector<Ball> balls;
  std::vector<BeamGeometry> beams;
  std::vector<std::int64_t> ball_index, beam_index;  // each element's index in the lattice's listing

  // ball_mask / beam_mask: over Lattice::balls() / beams(), nonzero keeps (nullptr keeps everything).
  explicit BruteForceQuery(const Lattice& lat, const std::uint8_t* ball_mask = nullptr,
                           const std::uint8_t* beam_mask = nullptr) {
    lat.for_each_ball([&](std::int64_t x, const NodeId&, const Ball& b) {
      if (ball_mask && !ball_mask[x]) return;
      balls.push_back(b);
      ball_index.push_back(x);
    });
    lat.for_each_beam([&](std::int64_t x, const BeamId&, const BeamGeometry& g) {
      if (beam_mask && !beam_mask[x]) return;
      beams.push_back(g);
      beam_index.push_back(x);
    });
  }
  // The indices of the elements meeting q, sorted (as LatticeQuery::query_ball returns them).
  BallQueryResult operator()(const Ball& q) const {
    BallQueryResult r;
    for (std::size_t x = 0; x < balls.size(); ++x)
      if (ball_meets_ball(q, balls[x])) r.balls.push_back(ball_index[x]);
    for (std::size_t x = 0; x < beams.size(); ++x)
      if (ball_meets_beam(q, beams[x])) r.beams.push_back(beam_index[x]);
    return r;
  }
  bool meets(const Ball& q) const {
    for (const Ball& e : balls)
      if (ball_meets_ball(q, e)) return true;
    for (const BeamGeometry& g : beams)
      if (ball_meets_beam(q, g)) return true;
    return false;
  }
};

}  // namespace steady::test
