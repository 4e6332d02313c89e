#pragma once
// A parallel sort that can be cancelled: tbb::parallel_sort runs to its end once started (20 s and more on the
// 10^8 grid entries of a 10^7-element lattice's broad phase, so Ctrl-C waited that long). Blocks are sorted in
// parallel, then merged pairwise in rounds, with a poll of the current progress per block and per round; the
// longest stretch without a poll is the last merge, one linear pass. The order is the same as std::sort's for
// keys without ties (elements that compare equal may come out in another order).
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
#include <vector>

#include "steady/core/progress.hpp"

namespace steady {

template <class T>
void cancellable_sort(std::vector<T>& v) {
  const std::size_t n = v.size();
  // 64 blocks or more (a poll each), none smaller than 2^16 elements (a sort that short needs no poll)
  const std::size_t block = std::max<std::size_t>(std::size_t(1) << 16, n / 64 + 1);
  const std::size_t blocks = (n + block - 1) / block;
  Progress* const caller = current_progress();
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    const ProgressScope scope(caller);
    poll_progress();
    std::sort(v.begin() + b * block, v.begin() + std::min(n, (b + 1) * block));
  });
  for (std::size_t width = block; width < n; width *= 2) {
    poll_progress();
    const std::size_t pairs = (n + 2 * width - 1) / (2 * width);
    tbb::parallel_for(std::size_t(0), pairs, [&](std::size_t p) {
      const ProgressScope scope(caller);
      poll_progress();
      const std::size_t lo = p * 2 * width, mid = std::min(n, lo + width), hi = std::min(n, lo + 2 * width);
      if (mid < hi) std::inplace_merge(v.begin() + lo, v.begin() + mid, v.begin() + hi);
    });
  }
}

}  // namespace steady
