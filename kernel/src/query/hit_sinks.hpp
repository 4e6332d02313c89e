#pragma once
// Internal to the query family: the two sinks every query answer is built from, written once.
#include <algorithm>

#include "steady/query/lattice_query.hpp"

namespace steady::detail {

// Stops at the first hit.
struct FirstHitSink : HitSink {
  bool found = false;
  bool on_hit(const ElementHit&) override {
    found = true;
    return false;
  }
};

// The sorted indices of the balls and beams `visit(sink)` reports.
template <class Visit>
BallQueryResult collect_hits(Visit&& visit) {
  struct Collecting : HitSink {
    BallQueryResult result;
    bool on_hit(const ElementHit& hit) override {
      (hit.is_beam ? result.beams : result.balls).push_back(hit.index);
      return true;
    }
  } sink;
  visit(static_cast<HitSink&>(sink));
  std::sort(sink.result.balls.begin(), sink.result.balls.end());
  std::sort(sink.result.beams.begin(), sink.result.beams.end());
  return std::move(sink.result);
}

// Whether `visit(sink)` reports any element (it is asked to stop at the first).
template <class Visit>
bool any_hit(Visit&& visit) {
  FirstHitSink sink;
  visit(static_cast<HitSink&>(sink));
  return sink.found;
}

}  // namespace steady::detail
