// A query-only tool, linked against steady_core and steady_query alone: if anything in those families needed
// OpenCASCADE or CGAL, this program would not link (test `link_query_only` also checks its shared libraries).
#include <cstdio>

#include "steady/steady.hpp"  // the umbrella header: it must not pull OpenCASCADE in

int main() {
  using namespace steady;
  const Lattice lattice = Lattice::incremental({{Vec3(0.0), 0.2}}, {{0, 1, 0, 0, 0}, {0, 0, 1, 0, 0}, {0, 0, 0, 1, 0}},
                                               {4, 4, 4}, Similarity::translation({1, 0, 0}),
                                               Similarity::translation({0, 1, 0}), Similarity::translation({0, 0, 1}));
  const Lattice copy = lattice_from_json(lattice_to_json(lattice));
  const LatticeQuery query(copy);
  const BallQueryResult near = query.query_ball(Ball{Vec3(1.5, 1.5, 1.5), 0.9});
  const auto hits = static_cast<long long>(near.balls.size() + near.beams.size());
  std::printf("balls %lld, beams %lld, elements near the centre %lld\n", static_cast<long long>(copy.ball_count()),
              static_cast<long long>(copy.beam_count()), hits);
  return hits > 0 ? 0 : 1;
}
