#pragma once
// Internal to the query family: the two sinks every query answer is built from, written once.
#include <algorithm>
#include <sstream>
#include <string>

#include "steady/core/memory_budget.hpp"
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

// Bytes per element of a query result: its int64 index in the kernel's vector, and again in the caller's copy
// (the Python module's array).
constexpr std::uint64_t kBytesPerHit = 16;
// Results grow unchecked up to this many elements (16 MB); past it each doubling of a vector is checked first.
constexpr std::size_t kUncheckedHits = std::size_t(1) << 20;

// Refuses a result of `elements` elements of the ball query `query` beyond the memory budget, naming the radius.
inline void require_result_memory(const Ball& query, std::uint64_t elements, const char* bound) {
  std::ostringstream what;
  what.precision(6);
  what << "query_ball(radius=" << query.radius << ", center=(" << query.center.x << ", " << query.center.y << ", "
       << query.center.z << ")): a result of " << bound << " " << elements << " balls and beams";
  require_memory(elements * kBytesPerHit, what.str(),
                 "query smaller balls (a region at a time), ask touches(), contains() or distance(), or use "
                 "properties() for sums over the lattice");
}

// The sorted indices of the balls and beams `visit(sink)` reports for the ball `query`. The vectors' growth is
// checked against the memory budget (a refusal names the radius) rather than left to end in std::bad_alloc.
template <class Visit>
BallQueryResult collect_hits(const Ball& query, Visit&& visit) {
  struct Collecting : HitSink {
    const Ball& query;
    BallQueryResult result;
    explicit Collecting(const Ball& q) : query(q) {}
    bool on_hit(const ElementHit& hit) override {
      std::vector<std::int64_t>& v = hit.is_beam ? result.beams : result.balls;
      if (v.size() == v.capacity() && v.size() >= kUncheckedHits)
        require_result_memory(query, 2 * (result.balls.size() + result.beams.size()), "more than");
      v.push_back(hit.index);
      return true;
    }
  } sink(query);
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
