#pragma once
// Internal: dense indices over a range with a sorted list of excluded values (omitted nodes, beams
// removed with them). rank maps a kept value to its index among kept values; unrank inverts it.
#include <algorithm>
#include <cstdint>
#include <vector>

namespace steady::detail {

// Number of kept values below x (x itself kept): x - #excluded < x.
inline std::int64_t rank_excluding(const std::vector<std::int64_t>& excluded, std::int64_t x) {
  return x - (std::lower_bound(excluded.begin(), excluded.end(), x) - excluded.begin());
}

// The kept value of rank r. excluded[q] - q is non-decreasing; the number q* of q with
// excluded[q] - q <= r is the count of excluded values below the answer, which is r + q*.
inline std::int64_t unrank_excluding(const std::vector<std::int64_t>& excluded, std::int64_t r) {
  std::int64_t lo = 0, hi = static_cast<std::int64_t>(excluded.size());
  while (lo < hi) {
    const std::int64_t mid = (lo + hi) / 2;
    if (excluded[mid] - mid <= r) lo = mid + 1;
    else hi = mid;
  }
  return r + lo;
}

}  // namespace steady::detail
