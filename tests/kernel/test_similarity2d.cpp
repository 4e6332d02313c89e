// The planar similarity between two point pairs (constructive-lattice-geometry.md 2.4.6) and its powers.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "steady/core/errors.hpp"
#include "steady/core/similarity2d.hpp"

namespace steady {
namespace {

TEST(Similarity2, PointPairsMapAToCAndBToD) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-10.0, 10.0);
  for (int trial = 0; trial < 5000; ++trial) {
    const Vec2 a(u(rng), u(rng)), b(u(rng), u(rng)), c(u(rng), u(rng)), d(u(rng), u(rng));
    const Similarity2 s = Similarity2::from_point_pairs(a, b, c, d);
    EXPECT_LT(glm::length(s.apply(a) - c), 1e-10);
    EXPECT_LT(glm::length(s.apply(b) - d), 1e-10);
    // scale and angle are those of CD against AB
    EXPECT_NEAR(s.scale(), glm::length(d - c) / glm::length(b - a), 1e-12 * s.scale());
    // (S^(1/3))^3 = S and S^a S^b = S^(a+b)
    const Similarity2 root = s.power(1.0 / 3.0);
    EXPECT_LT(glm::length((root * root * root).apply(a) - c), 1e-9);
    const Vec2 p(u(rng), u(rng));
    EXPECT_LT(glm::length((s.power(0.3) * s.power(0.9)).apply(p) - s.power(1.2).apply(p)), 1e-9);
    if (s.kind() == Similarity2Kind::Spiral) EXPECT_LT(glm::length(s.apply(s.fixed_point()) - s.fixed_point()), 1e-8);
  }
}

TEST(Similarity2, EqualVectorsGiveATranslation) {
  const Similarity2 s = Similarity2::from_point_pairs({0, 0}, {1, 2}, {5, 5}, {6, 7});
  EXPECT_EQ(s.kind(), Similarity2Kind::Translation);
  EXPECT_LT(glm::length(s.power(0.5).apply({0, 0}) - Vec2(2.5, 2.5)), 1e-15);
  EXPECT_THROW(s.fixed_point(), InvalidInput);
}

TEST(Similarity2, SpiralAboutACenter) {
  const Similarity2 s = Similarity2::spiral(M_PI / 2, 2.0, {1, 1});
  EXPECT_LT(glm::length(s.apply({2, 1}) - Vec2(1, 3)), 1e-15);
  EXPECT_LT(glm::length(s.fixed_point() - Vec2(1, 1)), 1e-15);
  EXPECT_EQ(s.kind(), Similarity2Kind::Spiral);
}

TEST(Similarity2, CoincidentPointsAreRefused) {
  EXPECT_THROW(Similarity2::from_point_pairs({1, 1}, {1, 1}, {0, 0}, {1, 0}), InvalidInput);
  EXPECT_THROW(Similarity2::from_point_pairs({0, 0}, {1, 0}, {2, 2}, {2, 2}), InvalidInput);
  EXPECT_THROW(Similarity2::from_point_pairs({NAN, 0}, {1, 0}, {2, 2}, {2, 3}), InvalidInput);
}

}  // namespace
}  // namespace steady
