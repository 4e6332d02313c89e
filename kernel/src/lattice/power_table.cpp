#include "lattice/power_table.hpp"

#include <algorithm>
#include <vector>

#include "steady/core/errors.hpp"

namespace steady::detail {

PowerTable::PowerTable(const Similarity& step, std::int64_t lo, std::int64_t hi) : step_(step), lo_(lo) {
  const std::int64_t entries = 2 * (hi - lo) + 1;
  if (entries <= 0 || entries > kMaxPowerTableEntries) return;
  // Tabulated outward from S^0: the margins beyond the lattice's groups may reach powers outside the supported
  // numerical range (a steep dilation); the table then stops short of them, and at() computes them on demand, so
  // only a use of such a power (an element that is not there) is refused.
  const std::int64_t zero = std::clamp<std::int64_t>(-2 * lo, 0, entries - 1);
  std::int64_t first = zero;
  std::vector<SimilarityTransform> up, down;
  try {
    for (std::int64_t h = zero; h < entries; ++h)
      up.push_back(step.power(0.5 * static_cast<double>(2 * lo + h)).transform());
  } catch (const InvalidInput&) {
  }
  try {
    for (std::int64_t h = zero - 1; h >= 0; --h, --first)
      down.push_back(step.power(0.5 * static_cast<double>(2 * lo + h)).transform());
  } catch (const InvalidInput&) {
  }
  table_.assign(down.rbegin(), down.rend());
  table_.insert(table_.end(), up.begin(), up.end());
  if (first % 2 != 0) {  // the table starts at an integer power (lo_ counts whole steps)
    table_.erase(table_.begin());
    ++first;
  }
  lo_ = lo + first / 2;
}

}  // namespace steady::detail
