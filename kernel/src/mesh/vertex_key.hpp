#pragma once
// Vertices matched bit for bit: pieces of a mesh made apart (a Boolean's result, a group's union, placed hubs) are
// joined where their vertices are the same doubles, with no tolerance.
#include <array>
#include <cstdint>
#include <cstring>

#include "steady/core/vec.hpp"

namespace steady {

using VertexKey = std::array<double, 3>;

inline VertexKey vertex_key(const Vec3& p) { return {p.x, p.y, p.z}; }

struct VertexKeyHash {
  std::size_t operator()(const VertexKey& k) const {
    std::size_t h = 0;
    for (double d : k) {
      std::uint64_t u;
      std::memcpy(&u, &d, sizeof u);
      h = (h ^ u) * 0x100000001b3ULL + (h >> 29);
    }
    return h;
  }
};

}  // namespace steady
