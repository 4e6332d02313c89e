#pragma once
// Candidate pairs of overlapping axis-aligned boxes, found with a uniform hash grid: each box is entered in the
// grid cells it covers, and a pair is reported once, by the cell holding the low corner of the two boxes'
// intersection. Cost O(n + pairs) for boxes of similar sizes (cell size: a high quantile of the box extents).
#include <cstdint>
#include <utility>
#include <vector>

#include "steady/core/vec.hpp"

namespace steady {

struct Box {
  Vec3 lo{0.0}, hi{0.0};
  bool overlaps(const Box& o) const {
    return lo.x <= o.hi.x && o.lo.x <= hi.x && lo.y <= o.hi.y && o.lo.y <= hi.y && lo.z <= o.hi.z && o.lo.z <= hi.z;
  }
};

// All pairs (i, j), i < j, whose boxes overlap (touching counts), in no particular order. Parallel.
std::vector<std::pair<std::int64_t, std::int64_t>> overlapping_box_pairs(const std::vector<Box>& boxes);

// The slow, obviously right twin (tests only): every pair.
std::vector<std::pair<std::int64_t, std::int64_t>> overlapping_box_pairs_brute_force(const std::vector<Box>& boxes);

}  // namespace steady
