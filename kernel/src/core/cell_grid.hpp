#pragma once
// Internal: items kept in the cubic cells of a uniform grid (hashed), for neighbour searches that look at the 27
// cells about a point: the crease points of a crowded hub's tessellation, the nodes near a connector or a rod.
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "steady/core/vec.hpp"

namespace steady {

template <class Item>
class CellGrid {
 public:
  explicit CellGrid(double cell) : cell_(cell) {}
  void add(const Vec3& p, Item item) { cells_[key(cell_of(p))].push_back(std::move(item)); }
  // Calls visit(item) for the items of the 27 cells about p (every item within one cell of p, and some farther)
  // until it returns true; returns whether it did.
  template <class Visit>
  bool any_near(const Vec3& p, Visit&& visit) const {
    const auto c = cell_of(p);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(key({c[0] + dx, c[1] + dy, c[2] + dz}));
          if (it == cells_.end()) continue;
          for (const Item& item : it->second)
            if (visit(item)) return true;
        }
    return false;
  }

 private:
  std::array<std::int64_t, 3> cell_of(const Vec3& p) const {
    return {static_cast<std::int64_t>(std::floor(p.x / cell_)), static_cast<std::int64_t>(std::floor(p.y / cell_)),
            static_cast<std::int64_t>(std::floor(p.z / cell_))};
  }
  // 21 bits per coordinate: cells far apart may share a key, which only adds items to look at.
  static std::uint64_t key(const std::array<std::int64_t, 3>& c) {
    return (static_cast<std::uint64_t>(c[0] & 0x1fffff) << 42) | (static_cast<std::uint64_t>(c[1] & 0x1fffff) << 21) |
           static_cast<std::uint64_t>(c[2] & 0x1fffff);
  }
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<Item>> cells_;
};

}  // namespace steady
