#pragma once
// Powers S^t of one lattice step at integer and half-integer t, tabulated over the lattice's index range
// (plus a margin for beams that end outside it) when that is small, and evaluated from the generator
// otherwise. O(count) doubles per direction: the only per-index data of the queries, never per element.
#include <cstdint>
#include <vector>

#include "steady/core/similarity.hpp"

namespace steady::detail {

class PowerTable {
 public:
  PowerTable() = default;
  // Tabulates S^(h / 2) for the half-integers h / 2 in [lo, hi].
  PowerTable(const Similarity& step, std::int64_t lo, std::int64_t hi);

  // S^t, bit-identical to step.power(t).transform() (the table holds exactly those values).
  SimilarityTransform at(std::int64_t t) const { return at_half(2 * t); }
  // S^(twice / 2).
  SimilarityTransform at_half(std::int64_t twice) const {
    const std::int64_t slot = twice - 2 * lo_;
    if (slot >= 0 && slot < static_cast<std::int64_t>(table_.size())) return table_[static_cast<std::size_t>(slot)];
    return step_.power(0.5 * static_cast<double>(twice)).transform();
  }
  // S^(twice / 2) applied to a point, without copying the tabulated transform.
  Vec3 apply_half(std::int64_t twice, const Vec3& p) const {
    const std::int64_t slot = twice - 2 * lo_;
    if (slot >= 0 && slot < static_cast<std::int64_t>(table_.size()))
      return table_[static_cast<std::size_t>(slot)].apply_point(p);
    return step_.power(0.5 * static_cast<double>(twice)).transform().apply_point(p);
  }
  const Similarity& step() const { return step_; }

 private:
  Similarity step_;
  std::int64_t lo_ = 0;
  std::vector<SimilarityTransform> table_;
};

// Tables larger than this many entries per direction are not built (the powers are then evaluated from
// the generator, ~0.1 us each): 2^18 entries of 104 bytes is 27 MB, far beyond the counts a lattice of a
// billion elements has along one direction (1000 to 10^5).
constexpr std::int64_t kMaxPowerTableEntries = std::int64_t(1) << 18;

}  // namespace steady::detail
