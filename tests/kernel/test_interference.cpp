// The exact element predicates against independent oracles: the distance to the hull of two balls is
// the minimum over the interpolated balls (the hull is their union), found by ternary search; the ray
// entry is checked by sphere tracing with that oracle distance.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "steady/query/interference.hpp"
#include "test_support.hpp"

namespace steady {
namespace {

// The hull of two balls is the union of the balls (a + t(b - a), ra + t(rb - ra)), t in [0, 1]; outside
// it the distance is the minimum over t of |p - c(t)| - r(t), a convex function of t.
double oracle_hull_distance(const Vec3& p, const Ball& a, const Ball& b) {
  auto f = [&](double t) {
    return glm::length(p - (a.center + t * (b.center - a.center))) - (a.radius + t * (b.radius - a.radius));
  };
  double lo = 0.0, hi = 1.0;
  for (int it = 0; it < 200; ++it) {
    const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    if (f(m1) < f(m2))
      hi = m2;
    else
      lo = m1;
  }
  return std::min({f(0.0), f(1.0), f(0.5 * (lo + hi))});
}

TEST(Interference, HullDistanceMatchesOracle) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int outside = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Ball a{test::random_vec(rng, 3.0), 0.05 + u01(rng)};
    const double len = trial % 10 == 0 ? 0.5 * u01(rng) : 0.2 + 3 * u01(rng);  // includes one-inside-other
    const Ball b{a.center + test::random_unit(rng) * len, 0.05 + u01(rng)};
    const Vec3 p = test::random_vec(rng, 5.0);
    const double d = distance_to_hull(p, a, b), o = oracle_hull_distance(p, a, b);
    // Inside, both are negative (not necessarily equal): only the sign and the zero set matter there.
    if (o > 1e-9) {
      ++outside;
      EXPECT_NEAR(d, o, 1e-9) << trial;
    } else if (o < -1e-9) {
      EXPECT_LT(d, 0.0) << trial;
    }
  }
  EXPECT_GT(outside, 10000);
}

TEST(Interference, TouchingCounts) {
  const Ball a{{0, 0, 0}, 1.0}, b{{4, 0, 0}, 0.5};
  // The query just touches ball a from the left, the cone from above, and ball b from the right.
  EXPECT_TRUE(ball_meets_ball({{-2, 0, 0}, 1.0}, a));
  EXPECT_FALSE(ball_meets_ball({{-2, 0, 0}, 1.0 - 1e-12}, a));
  EXPECT_TRUE(ball_meets_beam({{5.5, 0, 0}, 1.0}, BeamGeometry{a, b}));
  EXPECT_FALSE(ball_meets_beam({{5.5, 0, 0}, 1.0 - 1e-12}, BeamGeometry{a, b}));
  // Cylinder (equal radii): distance to the side is exact.
  const Ball c{{0, 0, 0}, 0.5}, d{{0, 0, 10}, 0.5};
  EXPECT_NEAR(distance_to_hull({2, 0, 5}, c, d), 1.5, 1e-15);
}

// Sphere tracing with the oracle distance: safe steps, converges to the entry point.
double oracle_ray_entry(const Vec3& o, const Vec3& dir, const Ball& a, const Ball& b) {
  double s = 0.0;
  for (int it = 0; it < 100000; ++it) {
    const double d = oracle_hull_distance(o + s * dir, a, b);
    if (d < 1e-11) return s;
    s += d;
    if (s > 100.0) return kNoHit;
  }
  return s;
}

TEST(Interference, RayEntryMatchesSphereTracing) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int hits = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Ball a{test::random_vec(rng, 2.0), 0.1 + u01(rng)};
    const Ball b{a.center + test::random_unit(rng) * (trial % 10 == 0 ? 0.3 : 0.2 + 3 * u01(rng)), 0.1 + u01(rng)};
    const Vec3 o = test::random_vec(rng, 8.0);
    // Aim near the beam so that many rays hit, some graze, some miss.
    const Vec3 target = a.center + u01(rng) * (b.center - a.center) + test::random_vec(rng, 1.5);
    const Vec3 dir = glm::normalize(target - o);
    const double s = ray_enters_hull(o, dir, a, b), oracle = oracle_ray_entry(o, dir, a, b);
    if (oracle == kNoHit) {
      // A miss, or a graze the sphere tracer cannot resolve: the exact entry must then be a near-tangent.
      if (s != kNoHit) EXPECT_LT(oracle_hull_distance(o + s * dir, a, b), 1e-7) << trial;
      continue;
    }
    ++hits;
    ASSERT_NE(s, kNoHit) << trial;
    EXPECT_NEAR(s, oracle, 1e-6 * (1 + oracle)) << trial;
    // The reported point lies on the boundary (or the origin is inside).
    if (s > 0.0) EXPECT_NEAR(distance_to_hull(o + s * dir, a, b), 0.0, 1e-9) << trial;
  }
  EXPECT_GT(hits, 1000);
}

TEST(Interference, RayEntryBall) {
  const Ball b{{0, 0, 5}, 1.0};
  EXPECT_DOUBLE_EQ(ray_enters_ball({0, 0, 0}, {0, 0, 1}, b), 4.0);
  EXPECT_EQ(ray_enters_ball({0, 0, 0}, {0, 0, -1}, b), kNoHit);
  EXPECT_EQ(ray_enters_ball({0, 0, 5.5}, {1, 0, 0}, b), 0.0);
  EXPECT_EQ(ray_enters_ball({0, 2, 0}, {0, 0, 1}, b), kNoHit);
}

}  // namespace
}  // namespace steady
