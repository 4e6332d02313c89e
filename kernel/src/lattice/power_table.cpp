#include "lattice/power_table.hpp"

namespace steady::detail {

PowerTable::PowerTable(const Similarity& step, std::int64_t lo, std::int64_t hi) : step_(step), lo_(lo) {
  const std::int64_t entries = 2 * (hi - lo) + 1;
  if (entries <= 0 || entries > kMaxPowerTableEntries) return;
  table_.resize(static_cast<std::size_t>(entries));
  for (std::int64_t h = 0; h < entries; ++h)
    table_[static_cast<std::size_t>(h)] = step.power(0.5 * static_cast<double>(2 * lo + h)).transform();
}

}  // namespace steady::detail
