#pragma once
// The volume of a region by sampling a box around it: an independent check of OpenCASCADE's Fuse where hubs are
// united (the properties' clusters, hub_union.cpp; the B-rep's groups, brep/hub_group.cpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <utility>

#include "steady/core/vec.hpp"

namespace steady {

// `samples` uniform points of the box [lo, hi] drawn with a fixed seed (so runs repeat), counted where `inside`
// holds: the volume estimate and its standard error.
template <class Inside>
std::pair<double, double> sampled_box_volume(const Vec3& lo, const Vec3& hi, int samples, std::uint64_t seed,
                                             Inside inside) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int hits = 0;
  for (int i = 0; i < samples; ++i) {
    const Vec3 p = lo + (hi - lo) * Vec3(unit(random), unit(random), unit(random));
    if (inside(p)) ++hits;
  }
  const double box = (hi.x - lo.x) * (hi.y - lo.y) * (hi.z - lo.z);
  const double fraction = static_cast<double>(hits) / samples;
  return {box * fraction, box * std::sqrt(std::max(fraction * (1.0 - fraction), 1.0 / samples) / samples)};
}

}  // namespace steady
