#pragma once
// Ball-interference queries on a BeCOTS lattice (steady/cots/becots_lattice.hpp) through the map-level BeCOTS
// RangeFinder: the groups whose bounding balls (every node ball, and a ball around every beam the group starts)
// may meet the query, found from their log-polar bounds about the map's apex in time independent of the counts;
// then the same exact tests as LatticeQuery.
//
// Stacks in O(1) (the dissertation's 6.3): the field keeps the angle between P - F and the axis, so each layer's
// elements lie in a shell of cones, the interval of that angle its template spans. The layers a query can meet are
// those whose interval meets the query's, looked up in a table of the angle's buckets: O(1) layers for a point or a
// small ball, however many layers the stack has, instead of one RangeFinder per layer. (Equivalent to the
// dissertation's projection of Q onto the line of A corners, and needs no regular spacing of the layers.)
//
// LatticeQuery finds the map itself (becots_map_of) and takes this path on its own ("becots", Auto's choice when it
// applies); the class is also usable directly with a known map.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "steady/cots/becots_map.hpp"
#include "steady/cots/becots_range.hpp"
#include "steady/lattice/lattice.hpp"
#include "steady/query/lattice_query.hpp"

namespace steady {

class BecotsLatticeQuery {
 public:
  // `lattice` must have been laid on `map` by becots_lattice (checked: its steps are the map's per-tile
  // similarities, applied in the order W U V, W a translation).
  BecotsLatticeQuery(const Lattice& lattice, const BecotsMap& map);

  // Calls sink.on_hit for every element meeting the closed ball (touching counts), with the lattice's own
  // indices, until it returns false; polls cancellation as LatticeQuery does. Returns the number of elements
  // tested exactly (LatticeQuery::last_candidate_count).
  std::int64_t visit(const Ball& query, HitSink& sink) const;
  // Exactly the elements meeting the closed ball (touching counts), as LatticeQuery::query_ball.
  BallQueryResult query_ball(const Ball& query) const;
  // The groups tested for this query: the candidates' count (for benchmarks and tests).
  std::int64_t candidate_groups(const Ball& query) const;
  // The layers whose shell of cones meets the query's (sorted), the only ones searched.
  std::vector<int> candidate_layers(const Ball& query) const;
  int layer_count() const { return static_cast<int>(layers_.size()); }

 private:
  Lattice lattice_;  // its own copy (cheap: the definition and shared pointers)
  std::vector<BecotsRangeFinder> layers_;  // layer k: the template's bounding balls moved by W^k
  // The layers by the angle to the axis: bucket b of [polar_lo_, polar_lo_ + buckets * polar_step_) lists the
  // layers whose interval meets it. Empty (every layer searched) when some layer's template holds the apex.
  double polar_lo_ = 0.0, polar_step_ = 1.0;
  std::vector<std::vector<int>> buckets_;
};

// The BeCOTS map a lattice was laid on, recovered from its steps: a steady brick applied in the order W U V with
// no placement, U and V spiral similarities (or a rotation and a dilation) about one apex and axis, W a
// translation; the map's corner A is the template's first node off the axis. Empty, with `reason` set, otherwise
// (the map is only a candidate: BecotsLatticeQuery's constructor checks it against the steps).
std::optional<BecotsMap> becots_map_of(const Lattice& lattice, std::string* reason);

}  // namespace steady
