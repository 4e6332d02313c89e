#pragma once
// Brute-force point membership in a flat lattice (every ball, every beam as the hull of its end balls): the
// reference the trimming tests' Monte Carlo estimates count with, independent of the B-rep.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include "steady/lattice/flat_lattice.hpp"

namespace steady::test {

// A node ball, or the convex hull of a beam's two end balls (the union of the balls interpolating them, so the
// distance to it is a convex function of the interpolation parameter: a ternary search finds its minimum).
inline bool in_lattice(const FlatLattice& f, const Vec3& p) {
  for (const Ball& b : f.balls)
    if (glm::length(p - b.center) <= b.radius) return true;
  for (const FlatBeam& b : f.beams) {
    const Vec3 a = f.balls[b.a].center, c = f.balls[b.b].center;
    // The hull lies between the segment thickened by the smaller and by the larger radius.
    const double t0 = std::clamp(glm::dot(p - a, c - a) / glm::dot(c - a, c - a), 0.0, 1.0);
    const double to_segment = glm::length(p - (a + t0 * (c - a)));
    if (to_segment > std::max(b.ra, b.rb)) continue;
    if (to_segment <= std::min(b.ra, b.rb)) return true;
    auto g = [&](double t) { return glm::length(p - (a + t * (c - a))) - (b.ra + t * (b.rb - b.ra)); };
    double lo = 0, hi = 1;
    for (int it = 0; it < 80; ++it) {
      const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
      (g(m1) < g(m2) ? hi : lo) = (g(m1) < g(m2) ? m2 : m1);
    }
    if (g(0.5 * (lo + hi)) <= 0) return true;
  }
  return false;
}

struct SampledVolume {
  double volume, sigma;  // the estimate and its standard error
};

// Volume of the lattice inside the cylinder of `radius` about the vertical line through (cx, cy), between heights
// z0 and z1, by sampling in_lattice over the cylinder's box.
inline SampledVolume volume_in_upright_cylinder(const FlatLattice& f, double cx, double cy, double radius, double z0,
                                               double z1, int samples, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(cx - radius, cx + radius), uy(cy - radius, cy + radius), uz(z0, z1);
  int hits = 0;
  for (int k = 0; k < samples; ++k) {
    const Vec3 p(ux(rng), uy(rng), uz(rng));
    hits += std::hypot(p.x - cx, p.y - cy) <= radius && in_lattice(f, p);
  }
  const double box = 4.0 * radius * radius * (z1 - z0), frac = double(hits) / samples;
  return {frac * box, std::sqrt(frac * (1 - frac) / samples) * box};
}

}  // namespace steady::test
