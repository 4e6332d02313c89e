#include "steady/lattice/broad_phase.hpp"
#include "steady/core/progress.hpp"
#include "lattice/cancellable_sort.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace steady {

namespace {

// Cells per axis are kept below 2^20 so a cell's three coordinates pack into one 64-bit key.
constexpr std::int64_t kMaxCellsPerAxis = std::int64_t(1) << 20;
// A box covering more cells than this is tested against every other box instead (rare: a few huge elements).
constexpr std::int64_t kMaxCellsPerBox = 512;
// The cell edge is this quantile of the boxes' largest extents: most boxes then cover at most 8 cells.
constexpr double kCellSizeQuantile = 0.75;

struct Grid {
  Vec3 origin{0.0};
  double cell = 1.0;
  std::array<std::int64_t, 3> coord(const Vec3& p) const {
    return {static_cast<std::int64_t>(std::floor((p.x - origin.x) / cell)),
            static_cast<std::int64_t>(std::floor((p.y - origin.y) / cell)),
            static_cast<std::int64_t>(std::floor((p.z - origin.z) / cell))};
  }
  static std::uint64_t key(std::int64_t i, std::int64_t j, std::int64_t k) {
    return (static_cast<std::uint64_t>(i) << 42) | (static_cast<std::uint64_t>(j) << 21) | static_cast<std::uint64_t>(k);
  }
};

}  // namespace

std::vector<std::pair<std::int64_t, std::int64_t>> overlapping_box_pairs_brute_force(const std::vector<Box>& boxes) {
  std::vector<std::pair<std::int64_t, std::int64_t>> out;
  const std::int64_t n = static_cast<std::int64_t>(boxes.size());
  for (std::int64_t i = 0; i < n; ++i)
    for (std::int64_t j = i + 1; j < n; ++j)
      if (boxes[i].overlaps(boxes[j])) out.emplace_back(i, j);
  return out;
}

std::vector<std::pair<std::int64_t, std::int64_t>> overlapping_box_pairs(const std::vector<Box>& boxes) {
  using Pair = std::pair<std::int64_t, std::int64_t>;
  const std::int64_t n = static_cast<std::int64_t>(boxes.size());
  if (n < 2) return {};
  Vec3 lo = boxes[0].lo, hi = boxes[0].hi;
  std::vector<double> extents(n);
  // The serial passes over the boxes take seconds at 10^7 boxes: each polls (Ctrl-C) every 2^16 boxes.
  constexpr std::int64_t kPollEvery = (std::int64_t(1) << 16) - 1;
  for (std::int64_t i = 0; i < n; ++i) {
    if ((i & kPollEvery) == 0) poll_progress();
    lo = glm::min(lo, boxes[i].lo);
    hi = glm::max(hi, boxes[i].hi);
    const Vec3 e = boxes[i].hi - boxes[i].lo;
    extents[i] = std::max({e.x, e.y, e.z});
  }
  const std::int64_t q = std::min<std::int64_t>(n - 1, static_cast<std::int64_t>(kCellSizeQuantile * n));
  std::nth_element(extents.begin(), extents.begin() + q, extents.end());
  Grid grid;
  grid.origin = lo;
  const double span = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  grid.cell = std::max({extents[q], span / static_cast<double>(kMaxCellsPerAxis - 2), 1e-300});

  // Entries (cell key, box); boxes spanning too many cells go to the list of large boxes.
  std::vector<std::int64_t> large;
  std::vector<std::int64_t> entry_count(n + 1, 0);
  for (std::int64_t i = 0; i < n; ++i) {
    if ((i & kPollEvery) == 0) poll_progress();
    const auto a = grid.coord(boxes[i].lo), b = grid.coord(boxes[i].hi);
    const std::int64_t cells = (b[0] - a[0] + 1) * (b[1] - a[1] + 1) * (b[2] - a[2] + 1);
    if (cells > kMaxCellsPerBox) {
      large.push_back(i);
      continue;
    }
    entry_count[i + 1] = cells;
  }
  for (std::int64_t i = 0; i < n; ++i) entry_count[i + 1] += entry_count[i];
  std::vector<std::pair<std::uint64_t, std::int64_t>> entries(entry_count[n]);
  Progress* const caller = current_progress();  // each stage takes seconds per million boxes: cancellable
  tbb::parallel_for(std::int64_t(0), n, [&](std::int64_t i) {
    const ProgressScope scope(caller);
    if ((i & 4095) == 0) poll_progress();
    if (entry_count[i + 1] == entry_count[i]) return;
    const auto a = grid.coord(boxes[i].lo), b = grid.coord(boxes[i].hi);
    std::int64_t at = entry_count[i];
    for (std::int64_t z = a[2]; z <= b[2]; ++z)
      for (std::int64_t y = a[1]; y <= b[1]; ++y)
        for (std::int64_t x = a[0]; x <= b[0]; ++x) entries[at++] = {Grid::key(x, y, z), i};
  });
  cancellable_sort(entries);  // keys (cell, box) have no ties: the same order as a sort that cannot be cancelled
  std::vector<std::int64_t> runs;
  for (std::int64_t e = 0; e < static_cast<std::int64_t>(entries.size()); ++e) {
    if ((e & kPollEvery) == 0) poll_progress();
    if (e == 0 || entries[e].first != entries[e - 1].first) runs.push_back(e);
  }
  runs.push_back(static_cast<std::int64_t>(entries.size()));

  tbb::enumerable_thread_specific<std::vector<Pair>> found;
  tbb::parallel_for(std::size_t(0), runs.size() - 1, [&](std::size_t r) {
    const ProgressScope scope(caller);
    if ((r & 1023) == 0) poll_progress();
    auto& out = found.local();
    const std::uint64_t cell = entries[runs[r]].first;
    for (std::int64_t x = runs[r]; x < runs[r + 1]; ++x)
      for (std::int64_t y = x + 1; y < runs[r + 1]; ++y) {
        const std::int64_t i = entries[x].second, j = entries[y].second;
        const Box &bi = boxes[i], &bj = boxes[j];
        if (!bi.overlaps(bj)) continue;
        // Report the pair only in the cell holding the low corner of the intersection of the two boxes.
        const auto c = grid.coord(glm::max(bi.lo, bj.lo));
        if (Grid::key(c[0], c[1], c[2]) != cell) continue;
        out.emplace_back(std::min(i, j), std::max(i, j));
      }
  });
  std::vector<Pair> pairs;
  for (auto& v : found) pairs.insert(pairs.end(), v.begin(), v.end());
  // Large boxes against everything (each pair once: against all small boxes, and large pairs with i < j).
  std::vector<char> is_large(n, 0);
  for (std::int64_t i : large) is_large[i] = 1;
  for (std::size_t li = 0; li < large.size(); ++li) {
    poll_progress();  // each large box against every box
    const std::int64_t i = large[li];
    for (std::int64_t j = 0; j < n; ++j) {
      if (j == i || (is_large[j] && j < i)) continue;
      if (boxes[i].overlaps(boxes[j])) pairs.emplace_back(std::min(i, j), std::max(i, j));
    }
  }
  return pairs;
}

}  // namespace steady
