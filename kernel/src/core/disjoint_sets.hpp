#pragma once
// Disjoint sets of 0..n-1 (union-find with path halving): the connected components of pairs, as the builders
// need them for hubs joined by short beams or by foreign contacts.
#include <cstdint>
#include <numeric>
#include <vector>

namespace steady {

class DisjointSets {
 public:
  explicit DisjointSets(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), std::size_t(0)); }
  std::size_t root(std::size_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void join(std::size_t a, std::size_t b) { parent_[root(a)] = root(b); }
  std::size_t size() const { return parent_.size(); }

 private:
  std::vector<std::size_t> parent_;
};

}  // namespace steady
