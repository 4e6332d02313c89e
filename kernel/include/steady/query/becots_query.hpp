#pragma once
// Ball-interference queries on a BeCOTS lattice (steady/cots/becots_lattice.hpp) through the map-level BeCOTS
// RangeFinder: for each layer, the groups whose bounding balls (every node ball, and a ball around every beam the
// group starts) may meet the query, found from their log-polar bounds about the map's apex in time independent of
// the counts; then the same exact tests as LatticeQuery. O(layers) per query, O(1) on a slab. The general query
// paths do not see the commuting BeCOTS steps (their O(u) and O(1) conditions fail), so on these lattices this is
// the fast path.
#include <vector>

#include "steady/cots/becots_map.hpp"
#include "steady/cots/becots_range.hpp"
#include "steady/lattice/lattice.hpp"
#include "steady/query/lattice_query.hpp"

namespace steady {

class BecotsLatticeQuery {
 public:
  // `lattice` must have been laid on `map` by becots_lattice (checked: its steps are the map's per-tile
  // similarities, applied in the order W U V).
  BecotsLatticeQuery(const Lattice& lattice, const BecotsMap& map);

  // Exactly the elements meeting the closed ball (touching counts), as LatticeQuery::query_ball.
  BallQueryResult query_ball(const Ball& query) const;
  // The groups tested for the last kind of query: the candidates' count (for benchmarks and tests).
  std::int64_t candidate_groups(const Ball& query) const;

 private:
  Lattice lattice_;  // its own copy (cheap: the definition and shared pointers)
  std::vector<BecotsRangeFinder> layers_;  // layer k: the template's bounding balls raised by W^k
};

}  // namespace steady
