#pragma once
// Shared helpers of the kernel tests: the largest entry of a matrix, seeded random similarities of every kind,
// and the largest round-trip error seen (printed at the end of a run for the issue notes).
#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "steady/core/similarity.hpp"

namespace steady::test {

// The bytes of a file, read whole ("" when it cannot be read: the test's expectations on it then fail).
inline std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// The largest absolute entry of a matrix (relative comparisons of inertia tensors).
inline double max_abs(const Mat3& m) {
  double v = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) v = std::max(v, std::abs(m[i][j]));
  return v;
}

inline Vec3 random_vec(std::mt19937_64& rng, double scale = 1.0) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return {u(rng), u(rng), u(rng)};
}

inline Vec3 random_unit(std::mt19937_64& rng) {
  for (;;) {
    const Vec3 v = random_vec(rng);
    const double l = glm::length(v);
    if (l > 0.1 && l <= 1.0) return v / l;
  }
}

// A random similarity of kind `kind_index` % 6, with angles up to `max_angle` (either sign).
inline Similarity random_similarity(std::mt19937_64& rng, int kind_index, double max_angle = 3.0) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const double angle = (2.0 * u01(rng) - 1.0) * max_angle;
  const double scale = std::exp((2.0 * u01(rng) - 1.0) * 0.5);
  const Vec3 axis = random_unit(rng), point = random_vec(rng, 5.0);
  switch (kind_index % 6) {
    case 0: return Similarity::translation(random_vec(rng, 3.0));
    case 1: return Similarity::rotation(angle, axis, point);
    case 2: return Similarity::screw(angle, axis, point, (2.0 * u01(rng) - 1.0) * 2.0);
    case 3: return Similarity::dilation(scale, point);
    case 4: return Similarity::swirl(angle, axis, point, scale);
    default: {  // a general composition
      return Similarity::swirl(angle, axis, point, scale) * Similarity::translation(random_vec(rng, 2.0));
    }
  }
}

// Largest distance between the images of the unit frame (origin and the three tips) under two maps.
inline double map_error(const Similarity& a, const Similarity& b) { return a.map_distance(b); }

// Collects the largest round-trip error of the property tests, reported when the test binary ends.
double& largest_round_trip_error();
inline void record_error(double e) { largest_round_trip_error() = std::max(largest_round_trip_error(), e); }

}  // namespace steady::test
